#pragma once
// How much of each catalogue star the eye sees against the sky behind it: one texel per star
// (shaders/star_weights.frag; texel i is star i of the star pass's vertex order, x = i % kWidth,
// y = i / kWidth), copied on the GPU into a buffer of four floats per star (the weight, and the
// weight times the air's transmittance in front of the star) that the star sprites take
// as a vertex attribute (shaders/stars.vert): a CPU rasteriser pays far more for a texture fetch
// per vertex, let alone a sky look-up per star per frame, than for an attribute. The same pass
// writes the star draw's indirect command: its count is one past the last star with any weight.
//
// The weights are a pure function of their inputs, which come from the snapshot: the sky-view
// table's (camera distance, Sun zenith cosine on its grid) and the camera -> centre and Sun
// directions, and the Moon's (its table's zenith cosine, its direction and light), rounded to a grid of 2^-14 per
// component (0.0035 degrees) before use. They are re-rendered only when one of these changes; with time at the real
// rate, a few times a second. Every channel computes the same weights in the same frame, whatever frames it rendered
// before.
#include <array>
#include <vector>

#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/star_sky.hpp"

namespace cupola {

class StarSkyWeights {
public:
    static constexpr int kWidth = 128;
    // stars: (unit world direction, visual magnitude) per star, in the star pass's order.
    explicit StarSkyWeights(const std::vector<glm::vec4>& stars);

    // Brings the weights up to date for this frame's sky (its table already current) and the
    // first star_count stars (the others get weight 0); restores the framebuffer binding and the
    // viewport. Returns true when it rendered.
    bool update(const StarSky& sky, int star_count);
    // Four floats per star (and per padding texel): the weight, and the weight times the air's
    // transmittance in front of the star per sRGB channel (for a star drawn after the sky).
    GLuint buffer() const { return buffer_; }
    // The indirect command of glDrawArraysIndirect (count, 1, 0, 0) for the stars with weight.
    GLuint draw_command() const { return draw_command_; }
    ~StarSkyWeights();
    StarSkyWeights(const StarSkyWeights&) = delete;
    StarSkyWeights& operator=(const StarSkyWeights&) = delete;
    long renders() const { return renders_; }

    // A unit vector rounded to the weights' grid and renormalised.
    static glm::vec3 on_grid(const glm::vec3& unit);

private:
    void set_uniforms(const StarSky& sky, const glm::vec3& center_dir, const glm::vec3& sun, int star_count);
    void set_moon_uniforms(const StarSky& sky, const glm::vec3& moon);
    GlTexture stars_, weights_;
    GlFramebuffer fbo_;
    GlProgram program_;
    GlEmptyVertexArray vao_;
    GLuint buffer_ = 0, draw_command_ = 0;
    std::array<float, 16> key_{};
    bool valid_ = false;
    long renders_ = 0;
};

}  // namespace cupola
