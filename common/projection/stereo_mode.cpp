#include "projection/stereo_mode.hpp"

#include <stdexcept>

namespace cupola {

const std::vector<std::string>& stereo_mode_names() {
    static const std::vector<std::string> names = {
        "mono", "left", "right", "side_by_side", "side_by_side_half", "top_bottom", "top_bottom_half", "anaglyph"};
    return names;
}

StereoMode stereo_mode_from_name(const std::string& name) {
    const auto& n = stereo_mode_names();
    for (size_t i = 0; i < n.size(); ++i)
        if (n[i] == name) return static_cast<StereoMode>(i);
    if (name == "quad_buffer")
        throw std::invalid_argument(
            "quad_buffer stereo is not available: Cupola renders through EGL, which has no quad-buffered "
            "(GL_STEREO) configs, and its KMS and headless outputs have no left and right back buffers; give "
            "each eye its own channel (left, right) or pack both (side_by_side, top_bottom)");
    throw std::invalid_argument("'" + name +
                                "' is not a stereo mode (mono, left, right, side_by_side, side_by_side_half, "
                                "top_bottom, top_bottom_half, anaglyph)");
}

int stereo_eye_count(StereoMode m) {
    return m == StereoMode::Mono || m == StereoMode::Left || m == StereoMode::Right ? 1 : 2;
}

double stereo_eye_side(StereoMode m, int index) {
    if (m == StereoMode::Mono) return 0.0;
    if (m == StereoMode::Left) return -1.0;
    if (m == StereoMode::Right) return 1.0;
    return index == 0 ? -1.0 : 1.0;
}

glm::ivec2 stereo_eye_size(StereoMode m, int width, int height) {
    if (m == StereoMode::SideBySideHalf) return {width / 2, height};
    if (m == StereoMode::TopBottomHalf) return {width, height / 2};
    return {width, height};
}

glm::ivec2 stereo_frame_size(StereoMode m, int width, int height) {
    if (m == StereoMode::SideBySide) return {2 * width, height};
    if (m == StereoMode::TopBottom) return {width, 2 * height};
    if (m == StereoMode::SideBySideHalf) return {2 * (width / 2), height};
    if (m == StereoMode::TopBottomHalf) return {width, 2 * (height / 2)};
    return {width, height};
}

glm::ivec4 stereo_eye_viewport(StereoMode m, int index, int width, int height) {
    const glm::ivec2 e = stereo_eye_size(m, width, height);
    const bool side = m == StereoMode::SideBySide || m == StereoMode::SideBySideHalf;
    const bool stacked = m == StereoMode::TopBottom || m == StereoMode::TopBottomHalf;
    if (side) return {index == 0 ? 0 : e.x, 0, e.x, e.y};
    if (stacked) return {0, index == 0 ? e.y : 0, e.x, e.y};
    return {0, 0, e.x, e.y};
}

}  // namespace cupola
