#pragma once
// Lets the GLSL files under shaders/shared/ compile as C++ with GLM, so the CPU and the GPU share
// one source for the shading functions (see shared_shading.hpp).
//
// Include this, then the .glsl files, inside namespace cupola::shading (and an anonymous
// namespace: GLSL has no `inline`, so the functions get internal linkage instead). Nothing is
// #defined for C++. The shared files keep to the subset both languages accept:
//   - no in/out/inout qualifiers, no swizzle assignment, no const arrays, no GLSL-only built-ins
//     beyond the ones below;
//   - literals like 1.0 are double in C++: scalar arithmetic is fine (it narrows on assignment or
//     return), and vector * 1.0 works through the mixed overloads below;
//   - a scalar routine needed in double too is written with the type `real` (float here and on
//     the GPU, where the file itself #defines it for GLSL only; shared/ray_sphere.glsl), and is
//     included once more with real = double where double is needed.
#include <glm/glm.hpp>

#include <cmath>
#include <vector>

namespace cupola::shading {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat3 = glm::mat3;
using mat4 = glm::mat4;
using real = float;         // the scalar of the files written for both precisions (see above)
using uint = unsigned int;  // 32 bits, wrapping like GLSL's

// Vector built-ins (glm) and the std scalar overloads glm re-exports.
using glm::abs;
using glm::acos;
using glm::asin;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::distance;
using glm::dot;
using glm::exp;
using glm::floor;
using glm::fract;
using glm::length;
using glm::log;
using glm::log2;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::pow;
using glm::sin;
using glm::smoothstep;
using glm::sqrt;
using glm::step;
using glm::tan;

// Scalar built-ins that take float; a double literal argument converts (GLSL semantics).
// (exp, sqrt, pow, asin, acos, ... on float come from the std overloads glm re-exports.)
inline float max(float a, float b) { return a > b ? a : b; }
inline float min(float a, float b) { return a < b ? a : b; }
inline float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
inline float mix(float a, float b, float t) { return a + (b - a) * t; }
inline float step(float edge, float x) { return x < edge ? 0.0f : 1.0f; }
inline float smoothstep(float e0, float e1, float x) {
    const float t = clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}
inline float atan(float y, float x) { return std::atan2(y, x); }
inline float abs(float x) { return std::fabs(x); }
inline float log2(float x) { return std::log2(x); }
inline float sign(float x) { return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f); }

// vecN (float) combined with a double literal, as GLSL allows.
template <glm::length_t L>
glm::vec<L, float> operator*(const glm::vec<L, float>& v, double s) {
    return v * static_cast<float>(s);
}
template <glm::length_t L>
glm::vec<L, float> operator*(double s, const glm::vec<L, float>& v) {
    return v * static_cast<float>(s);
}
template <glm::length_t L>
glm::vec<L, float> operator/(const glm::vec<L, float>& v, double s) {
    return v / static_cast<float>(s);
}
template <glm::length_t L>
glm::vec<L, float> operator+(const glm::vec<L, float>& v, double s) {
    return v + static_cast<float>(s);
}
template <glm::length_t L>
glm::vec<L, float> operator-(const glm::vec<L, float>& v, double s) {
    return v - static_cast<float>(s);
}
template <glm::length_t L>
glm::vec<L, float> max(const glm::vec<L, float>& v, double s) {
    return glm::max(v, static_cast<float>(s));
}
template <glm::length_t L>
glm::vec<L, float> min(const glm::vec<L, float>& v, double s) {
    return glm::min(v, static_cast<float>(s));
}
template <glm::length_t L>
glm::vec<L, float> clamp(const glm::vec<L, float>& v, double lo, double hi) {
    return glm::clamp(v, static_cast<float>(lo), static_cast<float>(hi));
}

// Textures for the shared code: a CPU image with GL's sampling rules (bilinear, clamp to edge,
// texel centres at (i + 0.5) / n), so tables sampled on the CPU read what the GPU reads.
struct Texture2DData {
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> texels;  // row-major, row 0 at v = 0
    const glm::vec4& at(int x, int y) const { return texels[static_cast<size_t>(y) * width + x]; }
};
// The GLSL sampler2D: a non-owning handle, cheap to pass by value like its GLSL namesake.
struct sampler2D {
    const Texture2DData* data = nullptr;
};
inline vec4 textureLod(sampler2D s, vec2 uv, double /*lod*/) {
    const Texture2DData& t = *s.data;
    const float x = uv.x * static_cast<float>(t.width) - 0.5f;
    const float y = uv.y * static_cast<float>(t.height) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    auto cx = [&](float i) { return static_cast<int>(std::fmin(std::fmax(i, 0.0f), static_cast<float>(t.width - 1))); };
    auto cy = [&](float i) {
        return static_cast<int>(std::fmin(std::fmax(i, 0.0f), static_cast<float>(t.height - 1)));
    };
    const int x0 = cx(fx), x1 = cx(fx + 1.0f), y0 = cy(fy), y1 = cy(fy + 1.0f);
    return glm::mix(glm::mix(t.at(x0, y0), t.at(x1, y0), ax), glm::mix(t.at(x0, y1), t.at(x1, y1), ax), ay);
}

}  // namespace cupola::shading
