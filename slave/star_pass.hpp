#pragma once
// Pass 1: the star field. Sizes and brightness are angular and cluster-wide (StarFieldConfig);
// see shaders/stars.{vert,frag} and shaders/shared/star_psf.glsl.
#include <memory>
#include <vector>

#include "channel_view.hpp"
#include "config/scene_config.hpp"
#include "gl_buffer.hpp"
#include "gl_program.hpp"
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
