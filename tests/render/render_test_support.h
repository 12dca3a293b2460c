#pragma once
// Shared by the render tests that draw: a headless context per test suite (the test is skipped,
// saying why, when this machine can make none), and measures of images.

#include "render/headless_context.h"
#include "render/image.h"

#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <string>

namespace substep::render::test {

/// The process's headless context, made once; nullptr (with the reason in `failure`) when no
/// backend works here.
inline GlContext* sharedContext(std::string& failure) {
    static std::string reason;
    static std::unique_ptr<GlContext> context = [] {
        try {
            return createHeadlessContext();
        } catch (const ContextError& error) {
            reason = error.what();
            return std::unique_ptr<GlContext>();
        }
    }();
    failure = reason;
    return context.get();
}

/// Skips the calling test when there is no headless context.
#define SUBSTEP_REQUIRE_CONTEXT(context)                                              \
    std::string contextFailure;                                                       \
    GlContext* context = ::substep::render::test::sharedContext(contextFailure);      \
    if (context == nullptr) GTEST_SKIP() << "no headless OpenGL: " << contextFailure; \
    context->makeCurrent()

/// Number of distinct RGB colours in the image.
inline std::size_t distinctColours(const Image& image) {
    std::set<uint32_t> colours;
    for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
        colours.insert(uint32_t(image.rgba[i]) << 16 | uint32_t(image.rgba[i + 1]) << 8 | image.rgba[i + 2]);
    }
    return colours.size();
}

/// Fraction of pixels whose largest channel difference exceeds `tolerance`.
inline double fractionDiffering(const Image& a, const Image& b, int tolerance) {
    std::size_t differing = 0;
    for (std::size_t i = 0; i + 3 < a.rgba.size(); i += 4) {
        int largest = 0;
        for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
        if (largest > tolerance) ++differing;
    }
    return static_cast<double>(differing) / static_cast<double>(a.rgba.size() / 4);
}

}  // namespace substep::render::test
