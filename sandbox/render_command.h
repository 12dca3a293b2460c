#pragma once
/// `substep render SCENE --frames LIST --out DIR [--size WxH]`: headless PNGs of a scene
/// (DESIGN.md's command contract). The scene is simulated from frame 0 (its initial state) with
/// its own dt, substeps and iterations; each listed frame is drawn on an EGL surfaceless context
/// (OSMesa where EGL cannot make one) and written whole to DIR/frame_NNNNN.png.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace substep {

/// The options as typed; checked by renderCommand, so every bad value gets a message naming it.
struct RenderOptions {
    std::string scene;
    std::string frames;
    std::string outDirectory;
    std::string size = "1280x720";
    std::vector<std::string> knobs;  ///< --set NAME=VALUE, in order
};

/// Accepted values: frame numbers up to kMaxRenderFrame, at most kMaxRenderImages images,
/// sides of 1 to kMaxImageSide pixels and at most kMaxImagePixels in all (4x multisampled colour
/// and depth take 32 bytes a pixel: the cap keeps that near half a gigabyte). The device may
/// allow less; that is checked too.
inline constexpr long long kMaxRenderFrame = 10'000'000;
inline constexpr std::size_t kMaxRenderImages = 100'000;
inline constexpr int kMaxImageSide = 8192;
inline constexpr long long kMaxImagePixels = 4096LL * 4096LL;

/// Width and height from "WxH". Throws UsageError naming --size.
std::pair<int, int> parseImageSize(const std::string& text);

/// The frames of a list like "0,40,120", with ranges "0-120" (every frame) and "0-120:40"
/// (every 40th), sorted and without repeats. Throws UsageError naming --frames.
std::vector<long long> parseFrameList(const std::string& text);

/// The file frame `frame` is written to: DIR/frame_00040.png (five digits at least).
std::string frameFileName(long long frame);

/// Declares `render` and its options on `app`, bound to `options`.
CLI::App* addRenderCommand(CLI::App& app, RenderOptions& options);

/// Renders. Returns the exit code: 0 success, 1 the state turned non-finite (the frames before
/// are written), 2 bad input, no OpenGL context, or an output that cannot be written.
int renderCommand(const RenderOptions& options);

}  // namespace substep
