#include "capture/image_diff.h"

#include <algorithm>
#include <cstdlib>

namespace substep::capture {

namespace {

/// The largest of the four channel differences at byte offset `at`.
int channelDifference(const render::Image& a, const render::Image& b, std::size_t at) {
    int largest = 0;
    for (std::size_t c = 0; c < 4; ++c)
        largest = std::max(largest, std::abs(int(a.rgba[at + c]) - int(b.rgba[at + c])));
    return largest;
}

}  // namespace

ImageComparison compareImages(const render::Image& golden, const render::Image& fresh,
                              int pixelTolerance) {
    ImageComparison result;
    if (golden.width != fresh.width || golden.height != fresh.height) {
        result.sizeDiffers = true;
        return result;
    }
    result.pixels = static_cast<long long>(golden.width) * golden.height;
    for (std::size_t at = 0; at < golden.rgba.size(); at += 4) {
        const int difference = channelDifference(golden, fresh, at);
        result.largest = std::max(result.largest, difference);
        if (difference > pixelTolerance) ++result.differing;
    }
    return result;
}

render::Image differenceHeatMap(const render::Image& golden, const render::Image& fresh,
                                int pixelTolerance) {
    render::Image map{.width = golden.width,
                      .height = golden.height,
                      .rgba = std::vector<uint8_t>(golden.rgba.size())};
    const bool sameSize = golden.width == fresh.width && golden.height == fresh.height;
    for (std::size_t at = 0; at < golden.rgba.size(); at += 4) {
        const int difference = sameSize ? channelDifference(golden, fresh, at) : 255;
        uint8_t* out = &map.rgba[at];
        if (difference <= pixelTolerance) {
            for (std::size_t c = 0; c < 3; ++c)
                out[c] = static_cast<uint8_t>(golden.rgba[at + c] / 4);
        } else {
            // 0..1 from just over the tolerance to 255: red rises first, then green (to yellow).
            const double s = 0.25 + 0.75 * static_cast<double>(difference) / 255.0;
            out[0] = static_cast<uint8_t>(std::min(255.0, 510.0 * s));
            out[1] = static_cast<uint8_t>(std::max(0.0, std::min(255.0, 510.0 * (s - 0.5))));
            out[2] = 0;
        }
        out[3] = 255;
    }
    return map;
}

}  // namespace substep::capture
