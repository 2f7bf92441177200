#include "scene_renderer.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <numbers>
#include <stdexcept>

#include "eclipse/shadow_casters.hpp"
#include "eclipse/umbra_light.hpp"
#include "frame_targets.hpp"
#include "passes/atmosphere_pass.hpp"
#include "passes/beyond_the_air.hpp"
#include "passes/eclipse_shadow_uniforms.hpp"
#include "passes/glare_halo_pass.hpp"
#include "passes/glare_pass.hpp"
#include "passes/glare_probe.hpp"
#include "passes/milky_way_pass.hpp"
#include "passes/moonlight.hpp"
#include "passes/painter_pass.hpp"
#include "passes/overlay_pass.hpp"
#include "passes/pattern_pass.hpp"
#include "passes/planet_point_pass.hpp"
#include "passes/render_pass.hpp"
#include "passes/star_pass.hpp"
#include "projection/dome_frame.hpp"
#include "scene/sky_positions.hpp"
#include "scene/snapshot_bodies.hpp"
#include "scene/star_catalog.hpp"
#include "shading/shared_shading.hpp"
#include "stereo_packer.hpp"

namespace cupola {

namespace {
AtmospherePass::Atmospheres load_atmospheres(const SceneConfig& scene) {
    AtmospherePass::Atmospheres out;
    for (const auto& b : scene.bodies)
        if (b.kind != BodyKind::Star && b.atmosphere.present) out[b.id] = std::make_unique<GpuAtmosphere>(b);
    return out;
}

std::map<uint16_t, glm::vec3> umbra_lights(const SceneConfig& scene, const AtmospherePass::Atmospheres& atmospheres) {
    std::map<uint16_t, glm::vec3> out;
    for (const auto& b : scene.bodies) {
        if (b.kind == BodyKind::Star) continue;
        const auto a = atmospheres.find(b.id);
        out[b.id] = umbra_light(b, a != atmospheres.end() ? &a->second->model() : nullptr);
    }
    return out;
}

bool scene_has_terrain(const SceneConfig& scene) {
    return std::any_of(scene.bodies.begin(), scene.bodies.end(), [](const BodyConfig& b) { return b.terrain.present; });
}

// Every body the snapshot names must be one of the scene's.
void check_body_ids(const Snapshot& snap, const SceneConfig& scene) {
    for (const auto& st : snap.bodies)
        if (st.id >= scene.bodies.size())
            throw std::runtime_error("snapshot names body id " + std::to_string(st.id) + " but the scene has " +
                                     std::to_string(scene.bodies.size()) + " bodies");
}
}  // namespace

struct SceneRenderer::Impl {
    Impl(const ClusterConfig& cluster, const ChannelConfig& ch, const SceneConfig& sc)
        : scene(sc),
          channel(ch),
          room(cluster.room),
          eye_size(stereo_eye_size(ch.stereo, ch.width, ch.height)),
          frustum(ch.orientation, ch.fov, eye_size.x, eye_size.y),
          camera_from_dome(dome_tilt_rotation(cluster.dome.tilt_deg)),
          tilt(camera_from_dome * channel_rotation(ch.orientation)),
          targets(eye_size.x, eye_size.y, scene_has_terrain(sc)) {
        if (stereo_eye_count(ch.stereo) == 2) packer = std::make_unique<StereoPacker>(ch.stereo, ch.width, ch.height);
        psf_sigma_rad = glm::radians(scene.stars.psf_sigma_arcmin / 60.0);
        coarsest_pixel_rad = pixel_angle_rad(frustum);
        for (const auto& c : cluster.channels)
            coarsest_pixel_rad = std::max(coarsest_pixel_rad, pixel_angle_rad(c.frustum()));
        point_to_disc_start = point_to_disc_start_rad(psf_sigma_rad, coarsest_pixel_rad);
        AtmospherePass::Atmospheres atmospheres = load_atmospheres(scene);
        tables = static_cast<int>(atmospheres.size());
        casting = std::make_unique<ShadowCasting>(scene, umbra_lights(scene, atmospheres));
        build_pipeline(cluster, ch, std::move(atmospheres));
    }

    // The pipeline, in the order it runs. What each pass reads and writes is its io(); the
    // targets each draw goes to follow from that (FrameTargets).
    void build_pipeline(const ClusterConfig& cluster, const ChannelConfig& ch, AtmospherePass::Atmospheres atm) {
        // The Milky Way, when the scene has one: colour, additive, behind everything.
        if (scene.milky_way.present)
            milky_way =
                &add(std::make_unique<MilkyWayPass>(scene.milky_way, scene.stars.zero_mag_flux, coarsest_pixel_rad));
        // Stars: colour, additive.
        std::vector<Star> catalog = load_star_catalog(scene.stars.catalog, scene.stars.magnitude_limit);
        // The overlays' star names come from the same catalogue, read once.
        const std::vector<Star> overlay_stars = scene.overlays.present ? catalog : std::vector<Star>{};
        stars = &add(std::make_unique<StarPass>(scene.stars, std::move(catalog)));
        // The Sun and the bodies, far to near: colour and G-buffer.
        painter = &add(std::make_unique<PainterPass>(scene, cluster, shadows));
        // The bodies too small for their disc alone: colour, additive, after the discs.
        planet_points = &add(std::make_unique<PlanetPointPass>());
        // The glare probe, into its own depth target: after every occluder, before what does not
        // occlude (the atmosphere).
        if (scene.glare.enabled)
            glare_probe = &add(std::make_unique<GlareProbe>(cluster, ch, scene, painter->bodies(), shadows));
        if (glare_probe) glare_probe->set_terrain(&painter->terrain());
        // The glare's halo at reduced resolution into its own target.
        GlareHaloPass* halo = nullptr;
        if (scene.glare.enabled && scene.glare.halo_downsample > 1)
            halo = &add(std::make_unique<GlareHaloPass>(scene, *glare_probe));
        // The atmospheres, one draw per body in view, far to near: colour and G-buffer in, colour
        // out; the nearest, when it covers the channel, adds the glare's halo in the same draw.
        if (!atm.empty()) {
            atmosphere = &add(std::make_unique<AtmospherePass>(std::move(atm), shadows, halo, &painter->bodies()));
            painter->set_surface_drawer(atmosphere);
            planet_points->set_sky_in_front(atmosphere);
            stars->set_sky_source(atmosphere);  // each star judged against the sky behind it
            if (milky_way) milky_way->set_sky_in_front(atmosphere);
        }
        // In a frame whose sky is drawn first, the stars and the Sun and bodies draw here instead
        // of in their own places above, each taking the air in front of it (beyond_the_air.hpp).
        if (atmosphere) {
            if (milky_way) add(std::make_unique<AfterTheSky>(*milky_way));
            add(std::make_unique<AfterTheSky>(*stars));
            add(std::make_unique<AfterTheSky>(*painter));
            add(std::make_unique<AfterTheSky>(*planet_points));
        }
        // The glare, last, from the cluster-wide visibility: colour, additive.
        if (scene.glare.enabled) add(std::make_unique<GlarePass>(scene, *glare_probe, halo));
        // The presenter's overlays, over everything: colour, blended.
        if (scene.overlays.present) overlays = &add(std::make_unique<OverlayPass>(scene, overlay_stars));
        // The alignment pattern, when the snapshot asks for one: replaces the colour of the passes
        // above, which are then skipped (render()); the passes after it (the output) draw it.
        pattern = &add(std::make_unique<PatternPass>(cluster, ch));
        FrameTargets::check_order(passes);
    }

    template <typename Pass>
    Pass& add(std::unique_ptr<Pass> pass) {
        Pass& p = *pass;
        passes.push_back(std::move(pass));
        return p;
    }

    FrameContext frame_context(const Snapshot& snap) const;
    // Where render() starts in the pass list: the first pass, or the pattern when one is on.
    size_t first_pass(const Snapshot& snap) const;

    // The frame's eye on this side of the snapshot's head (-1 left, 0 the head, +1 right): a channel
    // given as a screen is seen from it, and the scene from the camera moved as far as the eye is
    // from the room's origin; any other channel keeps its frustum, and a stereo eye moves from the
    // camera by its half of the eyes' separation across the head.
    void follow_head(const Snapshot& snap, double eye_side);
    // One eye's render: every pass, in order, into the targets.
    void draw_eye(const Snapshot& snap);

    SceneConfig scene;
    ChannelConfig channel;
    RoomConfig room;
    glm::ivec2 eye_size;     // one eye's image (the channel's, but for half-resolution stereo)
    ChannelFrustum frustum;  // this eye's (follow_head)
    glm::dmat3 camera_from_dome;
    glm::dmat3 tilt;                    // channel -> camera frame
    glm::dvec3 eye_offset_dome_m{0.0};  // this frame's eye from the camera, scene metres, dome frame
    FrameTargets targets;
    std::unique_ptr<StereoPacker> packer;    // a stereo frame of two eyes: their packing
    int tables = 0;                          // atmosphere table sets built or loaded
    std::unique_ptr<ShadowCasting> casting;  // which casters shadow which receiver, per frame (CPU, double)
    EclipseShadowUniforms shadows{scene};    // the eclipse table and uniforms of shadowed passes
    std::vector<std::unique_ptr<RenderPass>> passes;
    GlareProbe* glare_probe = nullptr;     // only when the scene has glare
    AtmospherePass* atmosphere = nullptr;  // only when some body has an atmosphere
    MilkyWayPass* milky_way = nullptr;
    StarPass* stars = nullptr;
    PainterPass* painter = nullptr;
    PlanetPointPass* planet_points = nullptr;
    double psf_sigma_rad = 0.0;        // the stars' PSF (cluster-wide)
    double point_to_disc_start = 0.0;  // planet_light.hpp: from the PSF and the cluster's coarsest pixel
    double coarsest_pixel_rad = 0.0;   // of every channel of the cluster: cluster-wide detail follows it
    void set_planet_lights(FrameContext& f) const;
    glm::dvec3 air_point_flux(const FrameContext& f, const FrameBody& planet, const PlanetLightInputs& in) const;
    PlanetShine planetshine_on(const FrameContext& f, const BodyConfig& body, const BodyState& state) const;
    PatternPass* pattern = nullptr;  // the passes before it draw the scene
    OverlayPass* overlays = nullptr;
    std::vector<GlareMeasurement> no_measurements;
    bool stars_see_the_sky = true;  // set_stars_see_the_sky(): a sky drawn first needs it
    // No pass of its own (insert_pass) draws colour before the atmosphere: a sky drawn first would
    // hide it.
    bool nothing_else_before_the_sky = true;
    void check_what_is_before_the_sky();
    uint64_t read_backs = 0;  // frames read back (read_back())
    bool timing = false;      // set_pass_timing()
    FrameTimings timings;     // the last timed frame
};

namespace {
using TimingClock = std::chrono::steady_clock;

double ms_since(TimingClock::time_point t0) {
    return std::chrono::duration<double, std::milli>(TimingClock::now() - t0).count();
}

// Waits for the GPU and adds the time since t0 to the pass's entry (a name seen twice sums up).
void record_pass(FrameTimings& t, const std::string& name, TimingClock::time_point t0) {
    glFinish();
    const double ms = ms_since(t0);
    for (auto& [n, v] : t.passes_ms)
        if (n == name) {
            v += ms;
            return;
        }
    t.passes_ms.emplace_back(name, ms);
}

// The part of a star's disc that the bodies nearer to the camera leave visible.
double star_visible_fraction_in(const FrameContext& f, const FrameBody& star) {
    const auto disc = [](const SphereView& s) {
        return SkyDisc{s.center_dir, s.sin_alpha >= 1.0 ? std::numbers::pi : sphere_angular_radius_rad(s.sin_alpha)};
    };
    std::vector<SkyDisc> nearer;
    for (const FrameBody& o : f.far_to_near)
        if (o.body->kind != BodyKind::Star && o.sphere.distance_m < star.sphere.distance_m)
            nearer.push_back(disc(o.sphere));
    return star_visible_fraction(disc(star.sphere), nearer, star.body->limb_darkening_u);
}

}  // namespace

// The frame as every pass sees it: the channel's view, the light (the first of the scene's
// stars in the snapshot), the bodies far to near and their eclipse shadows.
FrameContext SceneRenderer::Impl::frame_context(const Snapshot& snap) const {
    FrameContext f;
    f.snap = &snap;
    f.view.frustum = &frustum;
    f.view.channel_to_world = glm::mat3_cast(snap.camera_orientation) * tilt;
    f.view.world_to_channel = glm::transpose(f.view.channel_to_world);
    f.view.camera_position_m =
        snap.camera_position_m + glm::mat3_cast(snap.camera_orientation) * (camera_from_dome * eye_offset_dome_m);
    if (alignment_pattern_of(snap.settings.flags) != AlignmentPattern::Off) return f;  // no scene drawn
    check_body_ids(snap, scene);
    if (const BodyState* st = find_star(snap, scene)) {
        const BodyConfig& b = scene.bodies[st->id];
        f.light = {true, st->position_m, b.radius_m, b.radiance, b.limb_darkening_u};
    }
    for (const auto& st : snap.bodies) {
        const BodyConfig& b = scene.bodies[st.id];
        f.far_to_near.push_back({&st, &b, make_sphere_view(f.view, st.position_m, b.radius_m), PlanetLight{}});
    }
    std::stable_sort(f.far_to_near.begin(), f.far_to_near.end(),
                     [](const FrameBody& a, const FrameBody& b) { return a.sphere.distance_m > b.sphere.distance_m; });
    for (const auto& it : f.far_to_near)
        if (it.body->kind != BodyKind::Star)
            f.casters[it.body->id] = casting->casters_for(snap, it.body->id, f.view.world_to_channel);
    set_planet_lights(f);
    f.moonlight = brightest_moonlight(f);
    f.sky_first = atmosphere && stars_see_the_sky && nothing_else_before_the_sky && atmosphere->sky_first(f);
    return f;
}

void SceneRenderer::Impl::follow_head(const Snapshot& snap, double eye_side) {
    const glm::dvec3 across = snap.head.orientation * glm::dvec3(0.5 * room.eye_separation_m * eye_side, 0.0, 0.0);
    const glm::dvec3 eye = snap.head.position_m + across;
    if (!channel.screen) {  // a dome's or a calibrated projector's channel: the eye is the camera's
        eye_offset_dome_m = room.scale * across;
        return;
    }
    frustum = ChannelFrustum(channel.orientation, channel.frustum_seen_from(eye).fov(), eye_size.x, eye_size.y);
    eye_offset_dome_m = room.scene_offset_m(eye);
}

void SceneRenderer::Impl::set_planet_lights(FrameContext& f) const {
    PlanetLightInputs in;
    in.sun_position_m = f.light.position_m;
    in.sun_irradiance_1au = sun_irradiance(f.light, kAstronomicalUnit_m);
    in.camera_position_m = f.view.camera_position_m;
    in.psf_sigma_rad = psf_sigma_rad;
    in.handover_start_rad = point_to_disc_start;
    for (FrameBody& it : f.far_to_near) {
        if (it.body->kind == BodyKind::Star) {
            it.light = star_light(*it.body, *it.state, in);
            it.light.flux *= star_visible_fraction_in(f, it);
        }
        if (it.body->kind == BodyKind::Star) continue;
        in.map_mean_rgb = painter->bodies().map_mean_rgb(it.body->id);
        in.map_grid = painter->bodies().map_grid(it.body->id);
        if (it.body->atmosphere.present) {  // its light summed only while it is a point (with_air)
            const PlanetLight handover = handover_light(*it.body, *it.state, in);
            it.light = with_air(handover, handover.disc_weight < 1.0 ? air_point_flux(f, it, in) : glm::dvec3(0.0));
            continue;
        }
        const PlanetShine shine = planetshine_on(f, *it.body, *it.state);
        in.shine = &shine;
        it.light = planet_light(*it.body, *it.state, in);
    }
}

// A planet with air as a point: its air's disc for a distant observer, over a ground of the
// albedo times the map's lit, visible part (lit_map_ratio, as the planets without air take it).
glm::dvec3 SceneRenderer::Impl::air_point_flux(const FrameContext& f, const FrameBody& planet,
                                               const PlanetLightInputs& in) const {
    if (!atmosphere) return glm::dvec3(0.0);
    const glm::dquat to_body = glm::conjugate(planet.state->orientation);
    const glm::dvec3 p = planet.state->position_m;
    const double mean = shading::rec709_luminance(glm::vec3(in.map_mean_rgb));
    const double map = lit_map_ratio(in.map_grid, mean, to_body * glm::normalize(in.sun_position_m - p),
                                     to_body * glm::normalize(in.camera_position_m - p), 0.0);
    return atmosphere->point_flux(f, planet, planet.body->albedo * in.map_mean_rgb * map);
}

// The light of the body a moon circles (its shadow group's parent: the Earth on the Moon), if that
// body is in the snapshot.
PlanetShine SceneRenderer::Impl::planetshine_on(const FrameContext& f, const BodyConfig& body,
                                                const BodyState& state) const {
    PlanetShine shine;
    for (const ShadowGroupConfig& g : scene.shadows.groups) {
        if (std::find(g.children.begin(), g.children.end(), body.id) == g.children.end()) continue;
        for (const FrameBody& source : f.far_to_near) {
            if (source.body->id != g.parent) continue;
            const glm::dvec3 mean = painter->bodies().map_mean_rgb(g.parent);
            const double lum = shading::rec709_luminance(glm::vec3(mean));
            shine.position_m = source.state->position_m;
            shine.unit_color = lum > 0.0 ? mean / lum : glm::dvec3(1.0);
            shine.irradiance = planetshine_irradiance(*source.body, *source.state, lum, state.position_m,
                                                      f.light.position_m, sun_irradiance(f.light, kAstronomicalUnit_m));
        }
    }
    return shine;
}

void SceneRenderer::Impl::check_what_is_before_the_sky() {
    nothing_else_before_the_sky = true;
    for (const auto& p : passes) {
        if (p.get() == atmosphere) return;
        if (p->io().writes_color && !dynamic_cast<const BeyondTheAirPass*>(p.get()))
            nothing_else_before_the_sky = false;
    }
}

size_t SceneRenderer::Impl::first_pass(const Snapshot& snap) const {
    if (alignment_pattern_of(snap.settings.flags) == AlignmentPattern::Off) return 0;
    for (size_t i = 0; i < passes.size(); ++i)
        if (passes[i].get() == pattern) return i;
    return 0;
}

SceneRenderer::SceneRenderer(const ClusterConfig& cluster, const ChannelConfig& channel, const SceneConfig& scene)
    : impl_(std::make_unique<Impl>(cluster, channel, scene)) {}

SceneRenderer::~SceneRenderer() {
    if (impl_->atmosphere) {
        const AtmosphereStats s = atmosphere_stats();
        spdlog::info(
            "atmospheres: {} table sets built or loaded, {} passes run ({} marched), {} skipped (outside the "
            "frustum), {} sky-view tables rendered",
            s.tables_built_or_loaded, s.passes_run, s.passes_marched, s.passes_skipped, s.sky_view_renders);
    }
}

AtmosphereStats SceneRenderer::atmosphere_stats() const {
    AtmosphereStats s;
    s.tables_built_or_loaded = impl_->tables;
    if (impl_->atmosphere) {
        s.passes_run = impl_->atmosphere->draws_run();
        s.passes_skipped = impl_->atmosphere->draws_skipped();
        s.passes_marched = impl_->atmosphere->draws_marched();
        s.sky_view_renders = impl_->atmosphere->sky_view_renders();
        s.halos_added = impl_->atmosphere->halos_added();
        s.surfaces_drawn = impl_->atmosphere->surfaces_drawn();
    }
    return s;
}

const std::vector<GlareMeasurement>& SceneRenderer::glare_measurements() const {
    return impl_->glare_probe ? impl_->glare_probe->latest() : impl_->no_measurements;
}

std::vector<std::string> SceneRenderer::pass_names() const {
    std::vector<std::string> out;
    for (const auto& p : impl_->passes) out.push_back(p->name());
    return out;
}

void SceneRenderer::insert_pass(size_t position, std::unique_ptr<RenderPass> pass) {
    if (!pass) throw std::invalid_argument("insert_pass: no render pass given");
    auto& passes = impl_->passes;
    if (position > passes.size())
        throw std::out_of_range("render pass \"" + pass->name() + "\" inserted at " + std::to_string(position) +
                                " but the list has " + std::to_string(passes.size()) + " passes");
    const auto at = passes.insert(passes.begin() + static_cast<std::ptrdiff_t>(position), std::move(pass));
    try {
        FrameTargets::check_order(passes);
    } catch (...) {
        passes.erase(at);
        throw;
    }
    impl_->check_what_is_before_the_sky();
}

Image SceneRenderer::render(const Snapshot& snap) {
    draw(snap);
    if (!impl_->timing) return read_back();
    const auto t0 = TimingClock::now();
    Image image = read_back();
    impl_->timings.read_back_ms = ms_since(t0);
    impl_->timings.frame_ms += impl_->timings.read_back_ms;
    return image;
}

void SceneRenderer::set_pass_timing(bool on) { impl_->timing = on; }

void SceneRenderer::set_halo_with_atmosphere(bool on) {
    if (impl_->atmosphere) impl_->atmosphere->set_add_halo(on);
}

void SceneRenderer::set_surface_with_atmosphere(bool on) {
    if (impl_->atmosphere) impl_->atmosphere->set_draw_surfaces(on);
}

void SceneRenderer::set_stars_see_the_sky(bool on) {
    impl_->stars->set_sky_source(on ? impl_->atmosphere : nullptr);
    impl_->stars_see_the_sky = on;
}

void SceneRenderer::set_sky_first(bool on) {
    if (impl_->atmosphere) impl_->atmosphere->set_sky_first(on);
}

long SceneRenderer::star_weight_renders() const { return impl_->stars->sky_weight_renders(); }

const OverlayPass* SceneRenderer::overlays() const { return impl_->overlays; }

const FrameTimings& SceneRenderer::last_frame_timings() const { return impl_->timings; }

const GlTexture& SceneRenderer::color() const {
    return impl_->packer ? impl_->packer->frame_color() : impl_->targets.color();
}

Image SceneRenderer::read_back() {
    ++impl_->read_backs;
    return impl_->packer ? impl_->packer->read() : impl_->targets.read();
}

uint64_t SceneRenderer::read_backs() const { return impl_->read_backs; }

Image SceneRenderer::read_geometry() const { return impl_->targets.read_geometry(); }

TerrainDrawer& SceneRenderer::terrain() { return impl_->painter->terrain(); }

uint64_t SceneRenderer::geometry_clears() const { return impl_->targets.geometry_clears(); }

uint64_t SceneRenderer::color_clears() const { return impl_->targets.color_clears(); }

long SceneRenderer::planet_points_drawn() const { return impl_->planet_points->points_drawn(); }

void SceneRenderer::Impl::draw_eye(const Snapshot& snap) {
    const FrameContext frame = frame_context(snap);
    const size_t first = first_pass(snap);
    const bool geometry_read = std::any_of(passes.begin() + static_cast<std::ptrdiff_t>(first), passes.end(),
                                           [&](const auto& p) { return p->reads_geometry_in(frame); });
    targets.begin_frame(geometry_read, !frame.sky_first);
    for (size_t i = first; i < passes.size(); ++i) {
        RenderPass* pass = passes[i].get();
        const auto pass_t0 = timing ? TimingClock::now() : TimingClock::time_point{};
        const PassIo io = pass->io();
        const int steps = pass->prepare(frame);
        for (int step = 0; step < steps; ++step) {
            pass->draw(targets.bind_for(io), step);
            targets.drawn(io);
        }
        if (timing) record_pass(timings, pass->name(), pass_t0);
    }
}

// Each eye of the channel's stereo mode (one for mono), from the same snapshot; a stereo pair is
// packed into the frame after each eye. The glare is measured in the left eye only (a right-eye
// channel leaves it to its left twin): the cluster's sum stays one value per source.
void SceneRenderer::draw(const Snapshot& snap) {
    Impl& m = *impl_;
    const auto frame_t0 = m.timing ? TimingClock::now() : TimingClock::time_point{};
    if (m.timing) m.timings = FrameTimings{};
    const int eyes = stereo_eye_count(m.channel.stereo);
    for (int e = 0; e < eyes; ++e) {
        m.follow_head(snap, stereo_eye_side(m.channel.stereo, e));
        if (m.glare_probe) m.glare_probe->set_measuring(e == 0 && m.channel.stereo != StereoMode::Right);
        m.draw_eye(snap);
        if (m.packer) m.packer->place(e, m.targets.color());
    }
    glFinish();
    if (m.timing) m.timings.frame_ms = ms_since(frame_t0);
    for (const auto& pass : m.passes) pass->frame_finished();  // this frame's queries are done by now: no wait
}

}  // namespace cupola
