#pragma once
// The sky-view table on the GPU (shaders/sky_view.frag; the texels are those of
// shaders/shared/atmosphere_sky_view.glsl, as common/atmosphere/sky_view_table.hpp builds them
// on the CPU): three RGBA32F textures, rendered when the camera's distance from the planet centre
// or the Sun's zenith cosine there changes. Both come from the snapshot in double, the same on
// every channel, so every channel renders the same table; nothing of a channel's frustum enters.
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"

namespace cupola {

class GpuAtmosphere;

class GpuSkyViewTable {
public:
    explicit GpuSkyViewTable(const GpuAtmosphere& atmosphere);

    // Renders the table for (d_m, mu_s) unless it holds it already; restores the framebuffer
    // binding and the viewport. Returns true when it rendered.
    bool update(float d_m, float mu_s);
    // Binds parts 0..2 to units first_unit .. first_unit + 2.
    void bind(GLuint first_unit) const;
    glm::vec2 size() const { return glm::vec2(parts_[0].width(), parts_[0].height()); }
    long renders() const { return renders_; }

private:
    const GpuAtmosphere& atmosphere_;
    GlTexture parts_[3];
    GlFramebuffer fbo_;
    GlProgram program_;
    GlEmptyVertexArray vao_;
    float d_m_ = -1.0f, mu_s_ = 2.0f;  // what the table holds (none yet)
    long renders_ = 0;
};

}  // namespace cupola
