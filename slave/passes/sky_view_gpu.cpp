#include "passes/sky_view_gpu.hpp"

#include "gl/gl_api.hpp"
#include "passes/atmosphere_pass.hpp"
#include "passes/atmosphere_uniforms.hpp"

namespace cupola {

namespace {
GlTexture table_target(const atmosphere::ProductionQuality& q) {
    return GlTexture(q.sky_view_width, q.sky_view_height, nullptr, GL_LINEAR);
}
}  // namespace

GpuSkyViewTable::GpuSkyViewTable(const GpuAtmosphere& atmosphere)
    : atmosphere_(atmosphere),
      parts_{table_target(atmosphere.model().quality()), table_target(atmosphere.model().quality()),
             table_target(atmosphere.model().quality())},
      fbo_({&parts_[0], &parts_[1], &parts_[2]}),
      program_(
          "fullscreen.vert", "sky_view.frag",
          std::string("#define SKY_SIX_WAVELENGTHS ") + (atmosphere.model().six_wavelengths() ? "1" : "0") + "\n") {}

bool GpuSkyViewTable::update(float d_m, float mu_s) {
    if (d_m == d_m_ && mu_s == mu_s_) return false;
    const DrawTargetRestorer restore;
    const atmosphere::ProductionAtmosphere& m = atmosphere_.model();
    fbo_.bind();
    glDisable(GL_BLEND);
    program_.use();
    set_atmosphere_params(program_, m.shader_params());
    bind_atmosphere_tables(program_, atmosphere_, 0);
    if (m.six_wavelengths()) {
        set_atmosphere_params(program_, m.shader_params2(), "u_atm2");
        atmosphere_.bind_second(4);
        program_.set("u_transmittance2", 4);
        program_.set("u_multiple_scattering2", 5);
        program_.set("u_irradiance2", 6);
    }
    program_.set("u_d_m", d_m);
    program_.set("u_mu_s", mu_s);
    program_.set("u_table_size", size());
    program_.set("u_samples", m.quality().sky_view_samples);
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gl::check("sky-view table (" + m.parameters().name + ")");
    d_m_ = d_m;
    mu_s_ = mu_s;
    ++renders_;
    return true;
}

void GpuSkyViewTable::bind(GLuint first_unit) const {
    for (GLuint i = 0; i < 3; ++i) parts_[i].bind(first_unit + i);
}

}  // namespace cupola
