#pragma once
// What the planet and Moon tests measure in a rendered frame: a channel looking straight ahead,
// the frame's light (each pixel's luminance times its solid angle), and the frame written as a PNG
// for docs/images when CUPOLA_TEST_IMAGES=DIR is set.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "config/cluster_config.hpp"
#include "image/frame_image.hpp"
#include "wire/snapshot.hpp"

namespace cupola::test {

inline ChannelConfig straight_channel(double left_deg, double right_deg, int width, double up_down_deg = 20.0,
                                      int height = 256) {
    ChannelConfig ch;
    ch.fov = {left_deg, right_deg, up_down_deg, up_down_deg};
    ch.width = width;
    ch.height = height;
    return ch;
}

// Body 1 at the origin (pole +Z) and body 0 (the Sun) sun_distance_m along +X; the camera at
// delta_m along a direction at phase_deg from the Sun's in the equatorial plane, looking at body 1
// with +Z up; no exposure (every point drawn, its sprite out to a fixed reach).
inline Snapshot phase_view(double phase_deg, double sun_distance_m, double delta_m) {
    const double a = phase_deg * std::numbers::pi / 180.0;
    const glm::dvec3 to_camera(std::cos(a), std::sin(a), 0.0);
    Snapshot s;
    s.bodies.resize(2);
    s.bodies[1].id = 1;
    s.bodies[0].position_m = glm::dvec3(sun_distance_m, 0.0, 0.0);
    s.camera_position_m = to_camera * delta_m;
    s.settings.exposure = 0.0f;
    const glm::dvec3 back = to_camera, up(0, 0, 1), right = glm::normalize(glm::cross(up, back));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(back, right), back));
    return s;
}

// The frame's light: each pixel's radiance (luminance) times its solid angle.
inline double frame_flux(const Image& img, const ChannelConfig& ch) {
    const ChannelFrustum f = ch.frustum();
    const double sx = (f.tan_left() + f.tan_right()) / img.width, sy = (f.tan_down() + f.tan_up()) / img.height;
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double tx = -f.tan_left() + (x + 0.5) * sx, ty = f.tan_up() - (y + 0.5) * sy;
            const double q = 1.0 + tx * tx + ty * ty;
            const float* p = img.pixel(x, y);
            sum += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) * sx * sy / (q * std::sqrt(q));
        }
    return sum;
}

// Two channels side by side against one wide channel of their combined width (the same height):
// the largest difference of any colour component, and the wide frame's brightest component.
struct SeamDifference {
    double worst = 0.0, peak = 0.0;
};
inline SeamDifference seam_difference(const Image& left, const Image& right, const Image& wide) {
    SeamDifference d;
    for (int y = 0; y < wide.height; ++y)
        for (int x = 0; x < wide.width; ++x) {
            const float* narrow = x < left.width ? left.pixel(x, y) : right.pixel(x - left.width, y);
            for (int k = 0; k < 3; ++k) {
                d.worst = std::max(d.worst, double(std::abs(narrow[k] - wide.pixel(x, y)[k])));
                d.peak = std::max(d.peak, double(wide.pixel(x, y)[k]));
            }
        }
    return d;
}

// With CUPOLA_TEST_IMAGES=DIR, the frame goes to DIR/NAME/ as a PNG, scaled so that `peak` (its
// brightest value when 0) reads 1.
inline void maybe_write_frame(const std::string& name, Image img, float peak = 0.0f) {
    const char* dir = std::getenv("CUPOLA_TEST_IMAGES");
    if (!dir) return;
    if (peak <= 0.0f) {
        peak = 1e-30f;
        for (float v : img.rgba) peak = std::max(peak, v);
    }
    for (float& v : img.rgba) v /= peak;
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 1.0f;
    write_frame(std::string(dir) + "/" + name, img, FrameMetadata{}, {"png"}, 1.0);
}

}  // namespace cupola::test
