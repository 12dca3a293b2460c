#include "view/compare_session.h"

#include "physics/joint_projection.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

namespace substep::view {

namespace {

/// Frames one advance() may step. A scene slower than real time then runs slow but the window
/// stays responsive, instead of owing ever more steps (the "spiral of death").
constexpr int kMaxFramesPerAdvance = 4;

/// The largest substep or iteration count compare mode takes (the panel's sliders stop lower).
constexpr int kMaxSolverCount = 1000;

/// A whole number in [1, kMaxSolverCount] filling `text` exactly.
std::optional<int> parseCount(std::string_view text) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
    if (value < 1 || value > kMaxSolverCount) return std::nullopt;
    return value;
}

/// "SUBSTEPSxITERATIONS" with an optional ":paper" or ":start".
std::optional<SolverSplit> parseSplit(std::string_view text) {
    std::optional<JointProjection> projection;
    if (const std::size_t colon = text.find(':'); colon != std::string_view::npos) {
        projection = jointProjectionFromName(text.substr(colon + 1));
        if (!projection) return std::nullopt;
        text = text.substr(0, colon);
    }
    const std::size_t times = text.find('x');
    if (times == std::string_view::npos) return std::nullopt;
    const std::optional<int> substeps = parseCount(text.substr(0, times));
    const std::optional<int> iterations = parseCount(text.substr(times + 1));
    if (!substeps || !iterations) return std::nullopt;
    return SolverSplit{*substeps, *iterations, projection};
}

}  // namespace

std::optional<CompareSplits> parseCompareSplits(const std::string& text) {
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos) return std::nullopt;
    const std::string_view whole(text);
    const std::optional<SolverSplit> left = parseSplit(whole.substr(0, comma));
    const std::optional<SolverSplit> right = parseSplit(whole.substr(comma + 1));
    if (!left || !right) return std::nullopt;
    return CompareSplits{*left, *right};
}

CompareSession::CompareSession(SceneSource source, float aspect) : aspect_(aspect) {
    runs_.push_back(std::make_unique<ViewSession>(std::move(source), aspect_));
}

void CompareSession::compare(std::optional<CompareSplits> splits) {
    // Copies: the runs they come from are replaced.
    const SceneSource source = first().source();
    const SessionControls kept = first().controls();
    std::vector<std::string> plotted;  // the CSV columns plotted, kept in the new runs
    for (const ColumnPlots::Plot& plot : first().columnPlots().plots()) plotted.push_back(plot.column);
    if (splits) splits_ = *splits;
    const std::size_t count = splits ? 2 : 1;
    runs_.clear();
    for (std::size_t index = 0; index < count; ++index) {
        // Each run frames its start camera for its own part of the window.
        runs_.push_back(std::make_unique<ViewSession>(source, aspect_ / static_cast<float>(count)));
        runs_.back()->controls().gravityY = kept.gravityY;
        runs_.back()->controls().drawing = kept.drawing;
        for (const std::string& column : plotted) runs_.back()->columnPlots().add(column);
    }
    applySplits();
    applyControls();
    applyDrawingOptions();
    pendingSeconds_ = 0.0;
}

void CompareSession::applySplits() {
    if (!comparing()) return;
    for (std::size_t index = 0; index < runs_.size(); ++index) {
        run(index).controls().substeps = splits_[index].substeps;
        run(index).controls().iterations = splits_[index].iterations;
        if (splits_[index].jointProjection)
            run(index).controls().jointProjection = *splits_[index].jointProjection;
    }
}

void CompareSession::load(SceneSource source) {
    for (const std::unique_ptr<ViewSession>& each : runs_) each->load(source);
    // The new scene brings its own substeps and iterations; a comparison keeps what it compares.
    applySplits();
    applyControls();
    pendingSeconds_ = 0.0;
}

void CompareSession::restart() {
    for (const std::unique_ptr<ViewSession>& each : runs_) each->restart();
    pendingSeconds_ = 0.0;
}

void CompareSession::advance(double wallSeconds) {
    if (!playback_.playing) {
        pendingSeconds_ = 0.0;
        return;
    }
    // Playing shows no substep's corrections: their recording stops.
    for (const std::unique_ptr<ViewSession>& each : runs_) each->stopRecordingCorrections();
    const double dt = source().description.dt;
    pendingSeconds_ += wallSeconds * playback_.timeScale;
    int frames = 0;
    while (pendingSeconds_ >= dt && frames < kMaxFramesPerAdvance && playback_.playing) {
        stepOnce();
        pendingSeconds_ -= dt;
        ++frames;
    }
    // What could not be stepped now is dropped, not carried: the scene runs slow, then catches
    // nothing up in a burst.
    if (frames == kMaxFramesPerAdvance) pendingSeconds_ = 0.0;
}

void CompareSession::stepOnce() {
    // Lockstep: every run steps the same frame before the next one starts.
    for (const std::unique_ptr<ViewSession>& each : runs_) each->stepOnce();
    // A run that blew up stays put while the other goes on; with none left, playing stops.
    const bool anyFinite =
        std::any_of(runs_.begin(), runs_.end(), [](const std::unique_ptr<ViewSession>& each) { return each->finite(); });
    if (!anyFinite) playback_.playing = false;
}

namespace {

/// The substeps of the frame a run is in, or of the next one it begins.
int substepsOfFrame(const ViewSession& run) {
    return run.frameOpen() ? run.frameSubsteps() : std::max(run.world().settings().substeps, 1);
}

/// Where a run is within its frame: substeps done (0 between frames).
int substepsDone(const ViewSession& run) { return run.frameOpen() ? run.frameSubstepsDone() : 0; }

}  // namespace

void CompareSession::stepSubstep() {
    playback_.playing = false;
    pendingSeconds_ = 0.0;
    // The run with the most substeps per frame (the shortest h) leads and steps one substep;
    // every other run steps each of its substeps once the lead has reached that substep's end.
    // The runs then show the same moment (or the last substep each finished before it), and
    // reach every frame's end together: 20 x 1 against 1 x 20 steps the right run's one
    // substep with the left's twentieth.
    std::size_t lead = runs_.size();
    for (std::size_t index = 0; index < runs_.size(); ++index) {
        if (!run(index).finite()) continue;
        if (lead == runs_.size() || substepsOfFrame(run(index)) > substepsOfFrame(run(lead))) lead = index;
    }
    steppedLastSubstep_.assign(runs_.size(), false);
    if (lead == runs_.size()) return;
    run(lead).stepSubstep();
    steppedLastSubstep_[lead] = true;
    const long long frame = run(lead).frame();
    const long long leadSubsteps = substepsOfFrame(run(lead));
    const long long leadDone = substepsDone(run(lead));
    for (std::size_t index = 0; index < runs_.size(); ++index) {
        if (index == lead) continue;
        ViewSession& other = run(index);
        // Bounded: a frame has at most the solver's largest substep count.
        for (int guard = 0; guard < 100000 && other.finite(); ++guard) {
            if (other.frame() > frame) break;
            if (other.frame() == frame) {
                const long long substeps = substepsOfFrame(other);
                // Its next substep ends at (done + 1) / substeps of the frame; the lead is at
                // leadDone / leadSubsteps.
                if ((substepsDone(other) + 1) * leadSubsteps > leadDone * substeps) break;
            }
            const long long before = other.frame() * 100000 + substepsDone(other);
            other.stepSubstep();
            if (other.frame() * 100000 + substepsDone(other) == before) break;  // it could not step
            steppedLastSubstep_[index] = true;
        }
    }
}

void CompareSession::scrubBy(long long frames) {
    const long long target = first().frame() + frames;
    scrubTo(target);
    // Past the newest kept frame (or with nothing kept), new steps go on.
    while (first().frame() < target && first().finite()) stepOnce();
}

void CompareSession::scrubTo(long long frame) {
    playback_.playing = false;
    pendingSeconds_ = 0.0;
    for (const std::unique_ptr<ViewSession>& each : runs_) each->scrubTo(frame);
}

void CompareSession::applyControls() {
    const float gravityY = first().controls().gravityY;
    for (std::size_t index = 0; index < runs_.size(); ++index) {
        run(index).controls().gravityY = gravityY;
        run(index).applyControls();
        if (!comparing()) continue;
        // A split names its projection once one was asked for (--compare S×I:start, the panel).
        const JointProjection projection = run(index).controls().jointProjection;
        const bool named = splits_[index].jointProjection || projection != JointProjection::Paper;
        splits_[index] = {run(index).controls().substeps, run(index).controls().iterations,
                          named ? std::optional(projection) : std::nullopt};
    }
}

void CompareSession::applyDrawingOptions() {
    const DrawingOptions drawing = first().controls().drawing;
    for (const std::unique_ptr<ViewSession>& each : runs_) {
        each->controls().drawing = drawing;
        each->applyDrawingOptions();
    }
}

void CompareSession::setKnob(std::size_t index, double value) {
    for (const std::unique_ptr<ViewSession>& each : runs_) each->setKnob(index, value);
    if (comparing()) {
        applySplits();
        applyControls();
    }
}

void CompareSession::setJointCompliance(ecs::Entity joint, double compliance) {
    for (const std::unique_ptr<ViewSession>& each : runs_) each->setJointCompliance(joint, compliance);
}

render::RenderTarget CompareSession::target(std::size_t index, const render::RenderTarget& view) const {
    const int count = static_cast<int>(runs_.size());
    const int at = static_cast<int>(index);
    const int left = view.size.width * at / count;
    const int right = view.size.width * (at + 1) / count;
    return {.framebuffer = view.framebuffer,
            .size = {std::max(right - left, 1), view.size.height},
            .originX = view.originX + left,
            .originY = view.originY};
}

CompareSession::Part CompareSession::part(std::size_t index, const ViewArea& area) const {
    const float partWidth = area.width / static_cast<float>(runs_.size());
    return {area.left + partWidth * static_cast<float>(index), partWidth};
}

std::size_t CompareSession::runAt(float x, const ViewArea& area) const {
    if (area.width <= 0.0f) return 0;
    const float slot = std::floor((x - area.left) / area.width * static_cast<float>(runs_.size()));
    return static_cast<std::size_t>(std::clamp(slot, 0.0f, static_cast<float>(runs_.size() - 1)));
}

std::optional<std::size_t> CompareSession::dragging() const {
    for (std::size_t index = 0; index < runs_.size(); ++index) {
        if (run(index).dragging()) return index;
    }
    return std::nullopt;
}

}  // namespace substep::view
