#include "passes/sun_pass.hpp"

#include <algorithm>

namespace cupola {

SunPass::SunPass()
    : program_("sphere.vert", "sun.frag", "#define SUN_AFTER_SKY 0\n"),
      after_sky_("sphere.vert", "sun.frag", "#define SUN_AFTER_SKY 1\n") {}

void SunPass::draw(const ChannelView& view, const BodyConfig& body, const SphereView& sphere,
                   const SkyInFrontSource* sky, double weight, bool antialias_limb) {
    // The billboard covers the corona (kCoronaExtent radii, as shaders/sun.frag), unless the
    // corona is off or the camera is so close that the disc fills the view anyway.
    const double extent = body.corona > 0.0 ? kCoronaExtent : 1.0;
    SphereView cover = sphere;
    if (extent > 1.0 && sphere.sin_alpha * extent < 0.99)
        cover = make_sphere_view(
            view, view.camera_position_m + view.channel_to_world * (sphere.center_dir * sphere.distance_m),
            sphere.radius_m * extent);
    const GlProgram& p = sky ? after_sky_ : program_;
    p.use();
    p.set("u_radiance", glm::vec3(body.tint) * static_cast<float>(body.radiance));
    p.set("u_disc_weight", static_cast<float>(weight));
    p.set("u_limb_u", static_cast<float>(body.limb_darkening_u));
    p.set("u_disc_sin_alpha", static_cast<float>(std::min(sphere.sin_alpha, 1.0)));
    p.set("u_disc_distances_m", sphere_distances(sphere));
    p.set("u_corona", static_cast<float>(body.corona));
    p.set("u_limb_aa", antialias_limb ? 1 : 0);
    if (sky) sky->set_sky_in_front(p);
    // The disc and the corona add to the stars behind them, the coverage (alpha) unchanged; the
    // geometry attachment is not blended.
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    vao_.bind();
    draw_sphere(p, view, cover);
    glDisablei(GL_BLEND, 0);
    gl::check("sun pass (" + body.name + ")");
}

}  // namespace cupola
