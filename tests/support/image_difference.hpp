#pragma once
// How far apart two rendered images are.
#include <algorithm>
#include <cmath>

#include "image/frame_image.hpp"

namespace cupola::test {

// The largest difference between two images of one size over the brightest value of the first
// (1 when the first is black).
inline float relative_difference(const Image& a, const Image& b) {
    float brightest = 0.0f, worst = 0.0f;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        brightest = std::max(brightest, std::abs(a.rgba[i]));
        worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
    }
    return brightest > 0.0f ? worst / brightest : 1.0f;
}

}  // namespace cupola::test
