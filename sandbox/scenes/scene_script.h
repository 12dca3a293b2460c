#pragma once
/// What a built-in scene does beyond its bodies and joints: a hook before every frame (a rope
/// end turned, a robot's target moved) and the knobs and readouts of its own panel. Scripts know
/// nothing of ImGui: the viewer draws their knobs, and tests and commands set them by name, so
/// a scene behaves the same in the window, headless and under test.

#include "scene/scene.h"

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace substep {

/// One setting of a scene that is worth turning live.
struct SceneKnob {
    enum class Kind : unsigned char {
        Toggle,  ///< value 0 or 1
        Slider,  ///< value in [min, max]
        Choice,  ///< value the index of one of `choices`
    };
    std::string name;   ///< stable identifier, snake_case (tests and commands use it)
    std::string label;  ///< what the panel shows
    Kind kind = Kind::Slider;
    double value = 0.0;
    double min = 0.0;
    double max = 1.0;
    std::vector<std::string> choices;  ///< Choice only
    const char* format = "%.3g";       ///< Slider only: printf format of the value
    bool logarithmic = false;          ///< Slider only
};

/// A live value the panel shows under the knobs.
struct SceneReadout {
    std::string label;
    double value = 0.0;
    const char* format = "%.4g";
};

/// A knob the window drives from the keyboard (and a gamepad's stick, where GLFW sees one):
/// while a key of `positiveKeys` is held the knob is `rest + amount`, of `negativeKeys`
/// `rest - amount`; when they are let go it returns to `rest`. The stick sets it in proportion.
/// Keys are named by letters ("W") or "Up", "Down", "Left", "Right", separated by spaces.
/// Headless commands and tests ignore it: they set the knob by name.
struct SceneKeyAxis {
    std::string knob;
    std::string positiveKeys;
    std::string negativeKeys;
    double amount = 1.0;
    double rest = 0.0;
    int gamepadAxis = -1;        ///< GLFW gamepad axis index (0: left stick x, 1: left stick y); -1 none
    bool invertGamepad = false;  ///< the stick's positive direction lowers the knob
};

class SceneScript {
  public:
    virtual ~SceneScript() = default;

    /// After the scene is built, and again after every rebuild (a restart): puts the knobs'
    /// current values into the new world. Solver settings (substeps, iterations) are the
    /// caller's and are left alone here.
    virtual void start(SceneInstance& /*scene*/) {}
    /// Before each frame's step; `time` is the simulated time at the frame's start (s).
    virtual void beforeFrame(SceneInstance& /*scene*/, double /*time*/, double /*dt*/) {}
    /// Knob `index` changed while the scene runs: apply it (this may change solver settings).
    virtual void knobChanged(SceneInstance& /*scene*/, std::size_t /*index*/) {}
    /// Appends the values worth watching.
    virtual void readouts(const SceneInstance& /*scene*/, std::vector<SceneReadout>& /*out*/) const {}
    /// The camera the scene asks for in its current state (one following a body), or none to
    /// keep the scene's own or the viewer's.
    virtual std::optional<SceneCamera> camera(const SceneInstance& /*scene*/) const {
        return std::nullopt;
    }

    /// The knobs the window drives from the keyboard or a gamepad.
    std::span<const SceneKeyAxis> keyAxes() const { return keyAxes_; }
    /// A copy of the script with its state (knobs and what it keeps between frames), for the
    /// timeline's rewind; nullptr from a script that cannot be copied, whose scene then cannot
    /// be rewound exactly.
    virtual std::unique_ptr<SceneScript> clone() const { return nullptr; }

    std::span<SceneKnob> knobs() { return knobs_; }
    std::span<const SceneKnob> knobs() const { return knobs_; }
    /// The knob called `name`, or nullptr.
    SceneKnob* findKnob(std::string_view name);
    /// Sets knob `name` (clamped to its range) and applies it; false when there is no such knob.
    bool setKnob(SceneInstance& scene, std::string_view name, double value);

  protected:
    /// Declares a knob (in the constructor); returns its index.
    std::size_t addKnob(SceneKnob knob);
    /// Declares a knob the window drives from keys (in the constructor).
    void addKeyAxis(SceneKeyAxis axis) { keyAxes_.push_back(std::move(axis)); }
    double knob(std::size_t index) const { return knobs_[index].value; }
    bool toggled(std::size_t index) const { return knobs_[index].value != 0.0; }

  private:
    std::vector<SceneKnob> knobs_;
    std::vector<SceneKeyAxis> keyAxes_;
};

/// Makes a scene's script; a SceneEntry holds one for scenes that have a script.
using SceneScriptFactory = std::unique_ptr<SceneScript> (*)();

}  // namespace substep
