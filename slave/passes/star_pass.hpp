#pragma once
// Pass 1: the star field. Sizes and brightness are angular and cluster-wide (StarFieldConfig);
// see shaders/stars.{vert,frag} and shaders/shared/star_psf.glsl.
#include <memory>
#include <vector>

#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/channel_view.hpp"
#include "scene/star_catalog.hpp"

namespace cupola {

class StarPass {
public:
    // stars: any order (sorted here by magnitude so a limit is a prefix).
    StarPass(const StarFieldConfig& config, std::vector<Star> stars);
    // Adds the stars brighter than magnitude_limit into the bound framebuffer.
    void draw(const ChannelView& view, double magnitude_limit);

private:
    StarFieldConfig config_;
    std::vector<float> magnitudes_;  // ascending
    GlProgram program_;
    GlVertexBuffer vertices_;
};

}  // namespace cupola
