#include "atmosphere/auto_exposure.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/moonlit_sky.hpp"
#include "atmosphere/solar_scale.hpp"
#include "projection/dome_frame.hpp"
#include "scene/planet_magnitude.hpp"
#include "scene/sky_positions.hpp"
#include "scene/snapshot_bodies.hpp"

namespace cupola {

// The slaves light the night sky with the drawn light of the brightest body (slave/passes/
// moonlight.hpp); for the bodies with a measured phase curve (the Moon, the planets) that light is
// the curve's (a ringed Saturn's with its rings), which is what the exposure takes here, in units
// of the Sun's irradiance at 1 AU.
SkySecondLight AutoExposure::second_light(const Snapshot& snap, const BodyState& sun) const {
    SkySecondLight out;
    double best = 0.0;
    for (const BodyState& st : snap.bodies) {
        const BodyConfig& b = scene_->bodies[st.id];
        if (b.kind == BodyKind::Star || b.atmosphere.present) continue;
        const PlanetGeometry g = planet_geometry(st.position_m, st.orientation, sun.position_m, snap.camera_position_m);
        const std::optional<double> ratio = phase_curve_irradiance_ratio(
            b.ephemeris, b.radius_m, g, magnitude_includes_rings(b.ephemeris, b.rings.present));
        if (!ratio || !(*ratio > best)) continue;
        best = *ratio;
        out.present = true;
        out.position_m = st.position_m;
        out.irradiance_rgb = *ratio * sunlight_at_centre(casting_->casters_for(snap, st.id, glm::dmat3(1.0)));
    }
    return out;
}

AutoExposure::AutoExposure(const ClusterConfig& cluster, const SceneConfig& scene, const SceneAtmospheres* atmospheres)
    : cluster_(&cluster),
      scene_(&scene),
      atmospheres_(atmospheres),
      casting_(std::make_unique<ShadowCasting>(scene, std::map<uint16_t, glm::vec3>{})) {
    if (!cluster.output.auto_exposure.enabled || atmospheres_) return;
    own_atmospheres_ = std::make_unique<SceneAtmospheres>(scene);
    atmospheres_ = own_atmospheres_.get();
}

AutoExposure::~AutoExposure() = default;

std::vector<ChannelFrustum> AutoExposure::channel_frusta() const {
    std::vector<ChannelFrustum> frusta;
    for (const auto& ch : cluster_->channels) frusta.push_back(ch.frustum());
    return frusta;
}

std::vector<AutoExposure::MeterCell> AutoExposure::grid_cells(const std::vector<ChannelFrustum>& frusta, int grid) {
    std::vector<MeterCell> cells;
    for (size_t c = 0; c < frusta.size(); ++c) {
        const ChannelFrustum& f = frusta[c];
        const double dx = (f.tan_left() + f.tan_right()) / grid, dy = (f.tan_down() + f.tan_up()) / grid;
        for (int j = 0; j < grid; ++j)
            for (int i = 0; i < grid; ++i)
                cells.push_back(
                    {static_cast<int>(c), -f.tan_left() + (i + 0.5) * dx, -f.tan_down() + (j + 0.5) * dy, dx, dy});
    }
    return cells;
}

std::vector<AutoExposure::MeterRay> AutoExposure::meter_rays(const Snapshot& snap,
                                                             const std::vector<ChannelFrustum>& frusta,
                                                             const std::vector<MeterCell>& cells) const {
    const glm::dmat3 world_from_dome =
        glm::mat3_cast(snap.camera_orientation) * dome_tilt_rotation(cluster_->dome.tilt_deg);
    std::vector<MeterRay> rays;
    for (const MeterCell& cell : cells) {
        const glm::dvec3 dome_dir =
            glm::normalize(frusta[static_cast<size_t>(cell.channel)].rotation() * glm::dvec3(cell.x, cell.y, -1.0));
        int sharing = 0;
        for (const ChannelFrustum& g : frusta) sharing += g.contains(dome_dir) ? 1 : 0;
        rays.push_back({world_from_dome * dome_dir, image_plane_cell_solid_angle(cell.x, cell.y, cell.dx, cell.dy) /
                                                        static_cast<double>(std::max(sharing, 1))});
    }
    return rays;
}

// The cells of a grid x grid metering whose lit state differs from a neighbour's in the same
// channel: the edge of what is lit.
std::vector<size_t> AutoExposure::edge_cells(const std::vector<bool>& lit, int grid) {
    std::vector<size_t> out;
    const auto g = static_cast<size_t>(grid);
    for (size_t k = 0; k < lit.size(); ++k) {
        const size_t i = k % g, j = k / g % g;
        const bool edge = (i + 1 < g && lit[k + 1] != lit[k]) || (i > 0 && lit[k - 1] != lit[k]) ||
                          (j + 1 < g && lit[k + g] != lit[k]) || (j > 0 && lit[k - g] != lit[k]);
        if (edge) out.push_back(k);
    }
    return out;
}

// A cell cut into kRefine x kRefine.
void AutoExposure::split_cell(const MeterCell& c, std::vector<MeterCell>& out) {
    for (int j = 0; j < kRefine; ++j)
        for (int i = 0; i < kRefine; ++i)
            out.push_back({c.channel, c.x + ((i + 0.5) / kRefine - 0.5) * c.dx,
                           c.y + ((j + 0.5) / kRefine - 0.5) * c.dy, c.dx / kRefine, c.dy / kRefine});
}

std::vector<double> AutoExposure::luminances(const Snapshot& snap, const std::vector<MeterRay>& rays) const {
    std::vector<double> out(rays.size(), 0.0);
    const BodyState* sun_state = find_star(snap, *scene_);
    const BodyConfig& sun = scene_->bodies[sun_state->id];
    const SkySecondLight second = second_light(snap, *sun_state);  // the same for every atmosphere
    for (const auto& body : atmospheres_->bodies()) {
        const BodyState* st = find_body(snap, body->config->id);
        if (!st) continue;
        const glm::dvec3 to_centre = st->position_m - snap.camera_position_m;
        const double d = glm::length(to_centre);
        const glm::dvec3 c_hat = to_centre / d;
        const glm::dvec3 sun_dir = glm::normalize(sun_state->position_m - snap.camera_position_m);
        const double scale =
            atmosphere::solar_scale(body->model, sun, glm::length(sun_state->position_m - st->position_m));
        // Eclipse shadows on this body, relative to its centre in world axes (what the slaves do
        // in channel axes), so that the exposure opens up in totality.
        const shading::EclipseCasters casters = casting_->casters_for(snap, st->id, glm::dmat3(1.0));
        const double au_over_sun = kAstronomicalUnit_m / glm::length(sun_state->position_m - st->position_m);
        const MoonOnAir moon =
            moon_on_air(second, snap.camera_position_m, st->position_m,
                        glm::normalize(sun_state->position_m - st->position_m), au_over_sun * au_over_sun, body->model);
        // The night sky's own glow (shaders/shared/night_sky.glsl): cd/m^2 to scene units.
        const float height_m = static_cast<float>(d - body->model.shader_params().bottom_radius_m);
        const double to_scene = sun.radiance / atmosphere::kPhysicalSunRadiance_cd_m2;
        for (size_t k = 0; k < rays.size(); ++k) {
            const glm::dvec3& v = rays[k].dir_world;
            const auto start = shading::atm_ray_start(body->model.shader_params(), static_cast<float>(d), glm::vec3(v),
                                                      glm::vec3(c_hat), glm::vec3(sun_dir));
            if (snap.settings.night_sky_cd_m2 > 0.0f && start.valid &&
                !shading::atm_ray_hits_ground(body->model.shader_params(), start.r_m, start.mu))
                out[k] += to_scene * shading::night_sky_luminance(snap.settings.night_sky_cd_m2, height_m,
                                                                  static_cast<float>(glm::dot(v, -c_hat)));
            const shading::EclipseRay shadow =
                shading::eclipse_ray(casters, glm::vec2(1.0f),
                                     glm::vec3(-to_centre + v * static_cast<double>(start.offset_m)), glm::vec3(v));
            const glm::vec3 f = body->model.radiance(start, -1.0f, nullptr, shadow);
            out[k] += body->model.to_xyz(f).y * scale;
            if (moon.on) out[k] += moonlit_luminance(body->model, d, v, c_hat, moon) * scale;
        }
    }
    return out;
}

// A coarse grid, then the cells at the edge of what it found lit, refined: a thin lit limb seen
// from orbit falls between the rays of any regular grid (benchmarks/master_exposure).
SkyMetering AutoExposure::meter(const Snapshot& snap, int grid) const {
    if (!find_star(snap, *scene_) || !atmospheres_ || atmospheres_->empty()) return {};
    const std::vector<ChannelFrustum> frusta = channel_frusta();
    const std::vector<MeterCell> cells = grid_cells(frusta, grid);
    const std::vector<MeterRay> rays = meter_rays(snap, frusta, cells);
    const std::vector<double> l = luminances(snap, rays);
    std::vector<MeterSample> samples(rays.size());
    for (size_t k = 0; k < rays.size(); ++k) samples[k] = {l[k], rays[k].weight_sr};
    const SkyMetering coarse = meter_sky(samples);
    std::vector<bool> lit(cells.size());
    for (size_t k = 0; k < cells.size(); ++k)
        lit[k] = coarse.highlight > 0.0 && l[k] >= SkyMetering::kLitContrast * coarse.highlight;
    std::vector<bool> refined(cells.size(), false);
    std::vector<MeterCell> fine;
    for (size_t k : edge_cells(lit, grid)) {
        refined[k] = true;
        split_cell(cells[k], fine);
    }
    if (fine.empty()) return coarse;
    const std::vector<MeterRay> fine_rays = meter_rays(snap, frusta, fine);
    const std::vector<double> fine_l = luminances(snap, fine_rays);
    std::vector<MeterSample> all;  // a refined cell's samples replace its own
    for (size_t k = 0; k < cells.size(); ++k)
        if (!refined[k]) all.push_back(samples[k]);
    for (size_t k = 0; k < fine_rays.size(); ++k) all.push_back({fine_l[k], fine_rays[k].weight_sr});
    return meter_sky(all);
}

double AutoExposure::moonlit_luminance(const atmosphere::ProductionAtmosphere& model, double d_m, const glm::dvec3& v,
                                       const glm::dvec3& c_hat, const MoonOnAir& moon) {
    const auto start = shading::atm_ray_start(model.shader_params(), static_cast<float>(d_m), glm::vec3(v),
                                              glm::vec3(c_hat), glm::vec3(moon.dir_world));
    return model.to_xyz(model.radiance(start, -1.0f, nullptr)).y * shading::rec709_luminance(glm::vec3(moon.ratio_rgb));
}

ExposureDecision AutoExposure::decide(const Snapshot& snap, EyeAdaptation* eye, double dt_s) const {
    const AutoExposureConfig& ae = cluster_->output.auto_exposure;
    if (!ae.enabled) {
        ExposureDecision fixed;
        fixed.exposure = cluster_->output.exposure;
        return fixed;
    }
    const SkyMetering m = meter(snap);
    const double target = adaptation_target(m);
    return decide_exposure(m, eye ? eye->step(target, dt_s, ae) : target, ae);
}

}  // namespace cupola
