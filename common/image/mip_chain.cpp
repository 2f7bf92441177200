#include "image/mip_chain.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cupola {

namespace {

// The source texels that destination texel i of n_dst covers out of n_src, with their weights
// (overlap lengths in source texels, summing to n_src / n_dst).
struct Footprint {
    int first = 0;
    std::vector<float> weights;
};

std::vector<Footprint> footprints(int n_src, int n_dst) {
    std::vector<Footprint> out(static_cast<size_t>(n_dst));
    const double scale = static_cast<double>(n_src) / n_dst;
    for (int i = 0; i < n_dst; ++i) {
        const double lo = i * scale, hi = (i + 1) * scale;
        Footprint& f = out[static_cast<size_t>(i)];
        f.first = static_cast<int>(lo);
        for (int s = f.first; s < n_src && s < hi; ++s)
            f.weights.push_back(static_cast<float>(std::min<double>(s + 1, hi) - std::max<double>(s, lo)));
    }
    return out;
}

// Resamples along x: (w, h) -> (w_dst, h), each texel the weighted mean of its footprint.
std::vector<float> resample_rows(int w, int h, int nc, const std::vector<float>& texels, int w_dst) {
    const auto fp = footprints(w, w_dst);
    const float norm = static_cast<float>(w_dst) / static_cast<float>(w);
    std::vector<float> out(static_cast<size_t>(w_dst) * h * nc, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w_dst; ++x) {
            const Footprint& f = fp[static_cast<size_t>(x)];
            float* dst = &out[(static_cast<size_t>(y) * w_dst + x) * nc];
            for (size_t k = 0; k < f.weights.size(); ++k) {
                const float* src = &texels[(static_cast<size_t>(y) * w + f.first + k) * nc];
                for (int c = 0; c < nc; ++c) dst[c] += f.weights[k] * src[c];
            }
            for (int c = 0; c < nc; ++c) dst[c] *= norm;
        }
    return out;
}

// Resamples along y: (w, h) -> (w, h_dst).
std::vector<float> resample_columns(int w, int h, int nc, const std::vector<float>& texels, int h_dst) {
    const auto fp = footprints(h, h_dst);
    const float norm = static_cast<float>(h_dst) / static_cast<float>(h);
    const size_t row = static_cast<size_t>(w) * nc;
    std::vector<float> out(row * h_dst, 0.0f);
    for (int y = 0; y < h_dst; ++y) {
        const Footprint& f = fp[static_cast<size_t>(y)];
        float* dst = &out[row * y];
        for (size_t k = 0; k < f.weights.size(); ++k) {
            const float* src = &texels[row * (f.first + k)];
            for (size_t i = 0; i < row; ++i) dst[i] += f.weights[k] * src[i];
        }
        for (size_t i = 0; i < row; ++i) dst[i] *= norm;
    }
    return out;
}

void check_image(int width, int height, const std::vector<float>& texels, int channels) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("mip chain: image size " + std::to_string(width) + "x" + std::to_string(height) +
                                    " is not positive");
    if (channels < 1 || channels > 4)
        throw std::invalid_argument("mip chain: " + std::to_string(channels) + " channels is not in 1..4");
    const size_t expected = static_cast<size_t>(width) * height * channels;
    if (texels.size() != expected)
        throw std::invalid_argument("mip chain: a " + std::to_string(width) + "x" + std::to_string(height) + " " +
                                    (channels == 3 ? std::string("RGB") : std::to_string(channels) + "-channel") +
                                    " image needs " + std::to_string(expected) + " floats, got " +
                                    std::to_string(texels.size()));
}

// The common case, both sizes even: each texel the mean of its 2x2 block.
std::vector<float> halve_even(int w, int h, int nc, const std::vector<float>& texels) {
    const int w2 = w / 2, h2 = h / 2;
    const size_t row = static_cast<size_t>(w) * nc;
    std::vector<float> out(static_cast<size_t>(w2) * h2 * nc);
    for (int y = 0; y < h2; ++y) {
        const float* a = &texels[row * (2 * y)];
        const float* b = a + row;
        float* dst = &out[static_cast<size_t>(y) * w2 * nc];
        for (int x = 0; x < w2; ++x, a += 2 * nc, b += 2 * nc, dst += nc)
            for (int c = 0; c < nc; ++c) dst[c] = 0.25f * ((a[c] + a[c + nc]) + (b[c] + b[c + nc]));
    }
    return out;
}

// One level down: (width, height) -> (max(1, width / 2), max(1, height / 2)).
MipLevel box_filter_half(int width, int height, int nc, const std::vector<float>& texels) {
    MipLevel next;
    next.width = std::max(1, width / 2);
    next.height = std::max(1, height / 2);
    next.channels = nc;
    if (width % 2 == 0 && height % 2 == 0) {
        next.texels = halve_even(width, height, nc, texels);
        return next;
    }
    next.texels =
        resample_columns(next.width, height, nc, resample_rows(width, height, nc, texels, next.width), next.height);
    return next;
}

}  // namespace

std::vector<MipLevel> box_filter_mip_chain(int width, int height, const std::vector<float>& texels, int channels) {
    check_image(width, height, texels, channels);
    std::vector<MipLevel> chain;
    for (int w = width, h = height; w > 1 || h > 1; w = chain.back().width, h = chain.back().height)
        chain.push_back(box_filter_half(w, h, channels, chain.empty() ? texels : chain.back().texels));
    return chain;
}

}  // namespace cupola
