#include "passes/sun_pass.hpp"

#include <algorithm>

namespace cupola {

SunPass::SunPass() : program_("sphere.vert", "sun.frag") {}

void SunPass::draw(const ChannelView& view, const BodyConfig& body, const SphereView& sphere) {
    // The billboard covers the corona (kCoronaExtent radii, as shaders/sun.frag), unless the
    // corona is off or the camera is so close that the disc fills the view anyway.
    const double extent = body.corona > 0.0 ? kCoronaExtent : 1.0;
    SphereView cover = sphere;
    if (extent > 1.0 && sphere.sin_alpha * extent < 0.99)
        cover = make_sphere_view(
            view, view.camera_position_m + view.channel_to_world * (sphere.center_dir * sphere.distance_m),
            sphere.radius_m * extent);
    program_.use();
    program_.set("u_radiance", glm::vec3(body.tint) * static_cast<float>(body.radiance));
    program_.set("u_limb_u", static_cast<float>(body.limb_darkening_u));
    program_.set("u_disc_sin_alpha", static_cast<float>(std::min(sphere.sin_alpha, 1.0)));
    program_.set("u_disc_distances_m", sphere_distances(sphere));
    program_.set("u_corona", static_cast<float>(body.corona));
    // The corona adds to the stars behind it; the geometry attachment is not blended.
    glEnablei(GL_BLEND, 0);
    glBlendFunci(0, GL_ONE, GL_ONE);
    vao_.bind();
    draw_sphere(program_, view, cover);
    glDisablei(GL_BLEND, 0);
    gl::check("sun pass (" + body.name + ")");
}

}  // namespace cupola
