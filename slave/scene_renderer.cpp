#include "scene_renderer.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "body_pass.hpp"
#include "gl_framebuffer.hpp"
#include "projection/dome_frame.hpp"
#include "scene/star_catalog.hpp"
#include "sphere_billboard.hpp"
#include "star_pass.hpp"
#include "sun_pass.hpp"

namespace cupola {

struct SceneRenderer::Impl {
    Impl(const ClusterConfig& cluster, const ChannelConfig& ch, const SceneConfig& sc)
        : scene(sc),
          frustum(ch.frustum()),
          tilt(dome_tilt_rotation(cluster.dome.tilt_deg) * channel_rotation(ch.orientation)),
          framebuffer(ch.width, ch.height),
          stars(sc.stars, load_star_catalog(sc.stars.catalog, sc.stars.magnitude_limit)),
          bodies(sc) {}

    SceneConfig scene;
    ChannelFrustum frustum;
    glm::dmat3 tilt;  // channel -> camera frame
    GlFramebuffer framebuffer;
    StarPass stars;
    SunPass sun;
    BodyPass bodies;
};

SceneRenderer::SceneRenderer(const ClusterConfig& cluster, const ChannelConfig& channel, const SceneConfig& scene)
    : impl_(std::make_unique<Impl>(cluster, channel, scene)) {}

SceneRenderer::~SceneRenderer() = default;

Image SceneRenderer::render(const Snapshot& snap) {
    Impl& m = *impl_;
    ChannelView view;
    view.frustum = &m.frustum;
    view.channel_to_world = glm::mat3_cast(snap.camera_orientation) * m.tilt;
    view.world_to_channel = glm::transpose(view.channel_to_world);
    view.camera_position_m = snap.camera_position_m;

    m.framebuffer.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    // Pass 1: stars (background, additive).
    m.stars.draw(view, std::min<double>(m.scene.stars.magnitude_limit, snap.settings.star_magnitude_limit));

    // The light: the first BodyKind::Star in the snapshot.
    SunLight light;
    for (const auto& st : snap.bodies) {
        if (st.id >= m.scene.bodies.size()) throw std::runtime_error("snapshot names body id " + std::to_string(st.id) +
                                                                     " but the scene has " +
                                                                     std::to_string(m.scene.bodies.size()) + " bodies");
        const BodyConfig& b = m.scene.bodies[st.id];
        if (b.kind == BodyKind::Star && !light.present)
            light = {true, st.position_m, b.radius_m, b.radiance, b.limb_darkening_u};
    }

    // Passes 2 and 3: bodies far to near (painter's order); each disc is opaque and exact in
    // angle, so no depth buffer is needed between bodies.
    struct Item { const BodyState* state; const BodyConfig* body; SphereView sphere; };
    std::vector<Item> items;
    for (const auto& st : snap.bodies) {
        const BodyConfig& b = m.scene.bodies[st.id];
        items.push_back({&st, &b, make_sphere_view(view, st.position_m, b.radius_m)});
    }
    std::stable_sort(items.begin(), items.end(),
                     [](const Item& a, const Item& b) { return a.sphere.distance_m > b.sphere.distance_m; });
    for (const auto& it : items) {
        if (it.body->kind == BodyKind::Star)
            m.sun.draw(view, *it.body, it.sphere);
        else
            m.bodies.draw(view, *it.body, *it.state, it.sphere, light);
    }
    glFinish();
    return m.framebuffer.read();
}

}  // namespace cupola
