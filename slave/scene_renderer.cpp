#include "scene_renderer.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>
#include <stdexcept>

#include "passes/atmosphere_pass.hpp"
#include "passes/body_pass.hpp"
#include "eclipse/shadow_casters.hpp"
#include "eclipse/umbra_light.hpp"
#include "passes/eclipse_shadow_uniforms.hpp"
#include "gl/gl_framebuffer.hpp"
#include "passes/glare_pass.hpp"
#include "passes/glare_probe.hpp"
#include "projection/dome_frame.hpp"
#include "scene/star_catalog.hpp"
#include "passes/sphere_billboard.hpp"
#include "passes/star_pass.hpp"
#include "passes/sun_pass.hpp"

namespace cupola {

namespace {
std::map<uint16_t, std::unique_ptr<GpuAtmosphere>> load_atmospheres(const SceneConfig& scene) {
    std::map<uint16_t, std::unique_ptr<GpuAtmosphere>> out;
    for (const auto& b : scene.bodies)
        if (b.kind != BodyKind::Star && b.atmosphere.present) out[b.id] = std::make_unique<GpuAtmosphere>(b);
    return out;
}

double scene_sun_limb_u(const SceneConfig& scene) {
    for (const auto& b : scene.bodies)
        if (b.kind == BodyKind::Star) return b.limb_darkening_u;
    return 0.0;
}

std::map<uint16_t, glm::vec3> umbra_lights(const SceneConfig& scene,
                                           const std::map<uint16_t, std::unique_ptr<GpuAtmosphere>>& atmospheres) {
    std::map<uint16_t, glm::vec3> out;
    for (const auto& b : scene.bodies) {
        if (b.kind == BodyKind::Star) continue;
        const auto a = atmospheres.find(b.id);
        out[b.id] = umbra_light(b, a != atmospheres.end() ? &a->second->model() : nullptr);
    }
    return out;
}
}  // namespace

// Render targets: the scene is drawn into `color_a` (attachment 0) and `geometry` (attachment 1:
// reflectance + hit distance, for the atmosphere); each atmosphere pass then reads the latest
// colour and the geometry and writes the other colour texture (ping-pong). `target_a` and
// `target_b` hold one colour texture each, so no pass samples a texture attached to the
// framebuffer it draws into.
struct SceneRenderer::Impl {
    Impl(const ClusterConfig& cluster, const ChannelConfig& ch, const SceneConfig& sc)
        : scene(sc),
          frustum(ch.frustum()),
          tilt(dome_tilt_rotation(cluster.dome.tilt_deg) * channel_rotation(ch.orientation)),
          color_a(ch.width, ch.height, nullptr, GL_NEAREST),
          color_b(ch.width, ch.height, nullptr, GL_NEAREST),
          geometry(ch.width, ch.height, nullptr, GL_NEAREST),
          scene_target({&color_a, &geometry}),
          target_a({&color_a}),
          target_b({&color_b}),
          stars(sc.stars, load_star_catalog(sc.stars.catalog, sc.stars.magnitude_limit)),
          bodies(sc),
          atmospheres(load_atmospheres(sc)),
          casting(scene, umbra_lights(scene, atmospheres)),
          shadows(scene_sun_limb_u(scene)) {
        stats.tables_built_or_loaded = static_cast<int>(atmospheres.size());
        if (!atmospheres.empty()) atmosphere = std::make_unique<AtmospherePass>();
        if (sc.glare.enabled) {
            glare_probe = std::make_unique<GlareProbe>(cluster, ch, scene);
            glare = std::make_unique<GlarePass>(scene);
        }
    }

    SceneConfig scene;
    ChannelFrustum frustum;
    glm::dmat3 tilt;  // channel -> camera frame
    GlTexture color_a, color_b, geometry;
    GlFramebuffer scene_target, target_a, target_b;
    StarPass stars;
    SunPass sun;
    BodyPass bodies;
    std::map<uint16_t, std::unique_ptr<GpuAtmosphere>> atmospheres;  // by body id
    std::unique_ptr<AtmospherePass> atmosphere;                      // only when some body has one
    ShadowCasting casting;                    // which casters shadow which receiver, per frame (CPU, double)
    EclipseShadowUniforms shadows;            // the eclipse table and uniforms of the shadowed passes
    std::unique_ptr<GlareProbe> glare_probe;  // only when the scene has glare
    std::unique_ptr<GlarePass> glare;
    std::vector<GlareMeasurement> no_measurements;
    AtmosphereStats stats;
};

SceneRenderer::SceneRenderer(const ClusterConfig& cluster, const ChannelConfig& channel, const SceneConfig& scene)
    : impl_(std::make_unique<Impl>(cluster, channel, scene)) {}

SceneRenderer::~SceneRenderer() {
    if (!impl_->atmospheres.empty()) {
        const AtmosphereStats s = impl_->stats;
        spdlog::info("atmospheres: {} table sets built or loaded, {} passes run, {} skipped (outside the frustum)",
                     s.tables_built_or_loaded, s.passes_run, s.passes_skipped);
    }
}

AtmosphereStats SceneRenderer::atmosphere_stats() const { return impl_->stats; }

const std::vector<GlareMeasurement>& SceneRenderer::glare_measurements() const {
    return impl_->glare_probe ? impl_->glare_probe->latest() : impl_->no_measurements;
}

Image SceneRenderer::render(const Snapshot& snap) {
    Impl& m = *impl_;
    ChannelView view;
    view.frustum = &m.frustum;
    view.channel_to_world = glm::mat3_cast(snap.camera_orientation) * m.tilt;
    view.world_to_channel = glm::transpose(view.channel_to_world);
    view.camera_position_m = snap.camera_position_m;

    m.scene_target.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    m.scene_target.clear(0, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    m.scene_target.clear(1, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));  // distance < 0: no geometry

    // Pass 1: stars (background, additive; colour only, the geometry stays "none").
    m.scene_target.draw_buffers(1);
    m.stars.draw(view, std::min<double>(m.scene.stars.magnitude_limit, snap.settings.star_magnitude_limit));
    m.scene_target.draw_buffers(2);

    // The light: the first BodyKind::Star in the snapshot.
    SunLight light;
    for (const auto& st : snap.bodies) {
        if (st.id >= m.scene.bodies.size())
            throw std::runtime_error("snapshot names body id " + std::to_string(st.id) + " but the scene has " +
                                     std::to_string(m.scene.bodies.size()) + " bodies");
        const BodyConfig& b = m.scene.bodies[st.id];
        if (b.kind == BodyKind::Star && !light.present)
            light = {true, st.position_m, b.radius_m, b.radiance, b.limb_darkening_u};
    }

    // Passes 2 and 3: bodies far to near (painter's order); each disc is opaque and exact in
    // angle, so no depth buffer is needed between bodies.
    struct Item {
        const BodyState* state;
        const BodyConfig* body;
        SphereView sphere;
    };
    std::vector<Item> items;
    for (const auto& st : snap.bodies) {
        const BodyConfig& b = m.scene.bodies[st.id];
        items.push_back({&st, &b, make_sphere_view(view, st.position_m, b.radius_m)});
    }
    std::stable_sort(items.begin(), items.end(),
                     [](const Item& a, const Item& b) { return a.sphere.distance_m > b.sphere.distance_m; });
    // Eclipse shadows: per receiver, the casters whose penumbra reaches it this frame, in the
    // channel frame relative to the receiver's centre.
    std::map<uint16_t, shading::EclipseCasters> casters;
    for (const auto& it : items)
        if (it.body->kind != BodyKind::Star)
            casters[it.body->id] = m.casting.casters_for(snap, it.body->id, view.world_to_channel);
    for (const auto& it : items) {
        if (it.body->kind == BodyKind::Star)
            m.sun.draw(view, *it.body, it.sphere);
        else
            m.bodies.draw(view, *it.body, *it.state, it.sphere, light, m.shadows, casters[it.body->id]);
    }

    // The glare probe: after every occluder, before what does not occlude (the atmosphere).
    if (m.glare_probe) m.glare_probe->measure(snap, m.bodies, light, m.shadows);

    // Pass 4: atmospheres, far to near, each over everything drawn so far.
    const GlFramebuffer* current = &m.target_a;  // holds color_a, where the scene was drawn
    long run = 0, skipped = 0;
    for (const auto& it : items) {
        const auto atm = m.atmospheres.find(it.body->id);
        if (atm == m.atmospheres.end()) continue;
        const glm::dvec3 center = it.sphere.center_dir * it.sphere.distance_m;  // channel frame, double
        if (sphere_outside_frustum(m.frustum, center, atm->second->top_radius_m())) {
            ++skipped;
            continue;
        }
        const GlFramebuffer* next = current == &m.target_a ? &m.target_b : &m.target_a;
        next->bind();
        m.atmosphere->draw(view, *atm->second, *it.state, it.sphere, light, current->color(0), m.geometry, m.shadows,
                           casters[it.body->id]);
        current = next;
        ++run;
    }
    m.stats.passes_run += run;
    m.stats.passes_skipped += skipped;
    if (!m.atmospheres.empty())
        spdlog::debug("frame {}: atmosphere passes {} run, {} skipped (totals {} / {})", snap.frame, run, skipped,
                      m.stats.passes_run, m.stats.passes_skipped);
    // Pass 5: glare, last, without depth test, from the cluster-wide visibility.
    if (m.glare && !snap.glare.empty()) {
        current->bind();
        m.glare->draw(view, snap, *m.glare_probe);
    }
    glFinish();
    if (m.glare_probe) m.glare_probe->collect();  // this frame's queries are done by now: no wait
    return current->read();
}

}  // namespace cupola
