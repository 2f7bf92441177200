#include "sun_pass.hpp"

namespace cupola {

SunPass::SunPass() : program_("sphere.vert", "sun.frag") {}

void SunPass::draw(const ChannelView& view, const BodyConfig& body, const SphereView& sphere) {
    program_.use();
    program_.set("u_radiance", glm::vec3(body.tint) * static_cast<float>(body.radiance));
    program_.set("u_limb_u", static_cast<float>(body.limb_darkening_u));
    vao_.bind();
    draw_sphere(program_, view, sphere);
    gl::check("sun pass (" + body.name + ")");
}

}  // namespace cupola
