#pragma once
/// Comparing a rendered frame with its golden PNG: a pixel differs when any channel differs by
/// more than the tolerance; the fraction of such pixels is held against the capture's limit. The
/// heat map shows where and by how much, for the report.

#include "render/image.h"

namespace substep::capture {

struct ImageComparison {
    bool sizeDiffers = false;  ///< then nothing else is compared
    long long differing = 0;   ///< pixels with a channel off by more than the tolerance
    long long pixels = 0;
    int largest = 0;  ///< largest channel difference anywhere (0-255)
    double fraction() const {
        return pixels == 0 ? 0.0 : static_cast<double>(differing) / static_cast<double>(pixels);
    }
};

ImageComparison compareImages(const render::Image& golden, const render::Image& fresh,
                              int pixelTolerance);

/// The golden's size: each pixel's largest channel difference d. Pixels within the tolerance
/// show the golden dimmed to a quarter (for context), differing ones a ramp from dark red
/// (just over the tolerance) through red and orange to yellow (255).
render::Image differenceHeatMap(const render::Image& golden, const render::Image& fresh,
                                int pixelTolerance);

}  // namespace substep::capture
