#include "atmosphere/production_model.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "atmosphere/atmosphere_geometry.hpp"
#include "atmosphere/spectral_color.hpp"

namespace cupola::atmosphere {
using namespace cupola::shading;

namespace {
// Ozone: band averages rather than point values. The Chappuis band peaks near 600 nm, between
// the green and red samples, where the eye is most sensitive; point values at 550/680 nm miss
// it, which made long ozone paths (twilight, the ground seen from space) 5-15 % too bright.
// Each channel takes the mean over a hat function linear in lambda through the reconstruction's
// sample wavelengths `grid` (increasing; close to, not the same as, atm_samples_to_xyz's log-log
// reconstruction), weighted by the solar spectrum times the CIE y function.
double band_ozone(const AtmosphereParameters& p, double lambda, const std::vector<double>& grid) {
    double num = 0.0, den = 0.0;
    for (double l = 360.0; l <= 830.0; l += 1.0) {
        double hat = 0.0;
        for (std::size_t i = 0; i < grid.size(); ++i) {
            if (grid[i] != lambda) continue;
            const double lo = i > 0 ? grid[i - 1] : -1e9, hi = i + 1 < grid.size() ? grid[i + 1] : 1e9;
            if (l <= lambda)
                hat = i == 0 ? 1.0 : std::max(0.0, (l - lo) / (lambda - lo));
            else
                hat = i + 1 == grid.size() ? 1.0 : std::max(0.0, (hi - l) / (hi - lambda));
        }
        const double w = p.solar_irradiance(l) * cie1931_xyz_bar(l).y;
        num += hat * w * p.ozone_absorption(l);
        den += hat * w;
    }
    return num / std::max(den, 1e-300);
}
}  // namespace

AtmosphereParams to_shader_params(const AtmosphereParameters& p) {
    return to_shader_params(p,
                            glm::dvec3(kProductionWavelengths[0], kProductionWavelengths[1], kProductionWavelengths[2]),
                            {kProductionWavelengths[2], kProductionWavelengths[1], kProductionWavelengths[0]});
}

AtmosphereParams to_shader_params(const AtmosphereParameters& p, const glm::dvec3& lambdas_nm,
                                  const std::vector<double>& grid_nm) {
    auto at3 = [&](auto fn) {
        return vec3(static_cast<float>(fn(lambdas_nm.x)), static_cast<float>(fn(lambdas_nm.y)),
                    static_cast<float>(fn(lambdas_nm.z)));
    };
    AtmosphereParams a{};
    a.bottom_radius_m = static_cast<float>(p.bottom_radius);
    a.top_radius_m = static_cast<float>(p.top_radius);
    a.rayleigh_scattering_per_m = at3([&](double l) { return p.rayleigh_scattering(l); });
    a.rayleigh_scale_height_m = static_cast<float>(p.rayleigh_scale_height);
    a.mie_scattering_per_m = at3([&](double l) { return p.mie_scattering(l); });
    a.mie_extinction_per_m = at3([&](double l) { return p.mie_extinction(l); });
    a.mie_scale_height_m = static_cast<float>(p.mie_scale_height);
    a.mie_g = static_cast<float>(p.mie_g);
    a.ozone_absorption_per_m = at3([&](double l) { return band_ozone(p, l, grid_nm); });
    a.ozone_bottom_m = static_cast<float>(p.ozone_bottom);
    a.ozone_peak_m = static_cast<float>(p.ozone_peak);
    a.ozone_top_m = static_cast<float>(p.ozone_top);
    a.ground_albedo = at3([&](double l) { return p.ground_albedo(l); });
    return a;
}

std::vector<double> sky_view_wavelength_grid() {
    std::vector<double> g(kProductionWavelengths, kProductionWavelengths + 3);
    g.insert(g.end(), kProductionWavelengths2, kProductionWavelengths2 + 3);
    std::sort(g.begin(), g.end());
    return g;
}

AtmosphereAnalyticFit fit_analytic_sun(const AtmosphereParams& a) {
    const float r = a.bottom_radius_m + 0.5f * a.rayleigh_scale_height_m;
    constexpr int kAngles = 111;
    std::vector<glm::vec3> target(kAngles);
    for (int i = 0; i < kAngles; ++i) {
        const float mu_s = std::cos(glm::radians(static_cast<float>(i)));
        target[i] = atm_ray_hits_ground(a, r, mu_s) ? vec3(0.0f) : atm_compute_transmittance(a, r, mu_s, 200);
    }
    AtmosphereAnalyticFit best{vec3(1.6f), 8.0f};
    double best_err = 1e300;
    for (float k2 = 2.0f; k2 <= 80.0f; k2 += 1.0f) {
        AtmosphereAnalyticFit f{vec3(0.0f), k2};
        double total = 0.0;
        for (int c = 0; c < 3; ++c) {  // k1 per wavelength: fine grid over 1.0 .. 2.0 rad
            double best_c = 1e300;
            float best_k1 = 1.6f;
            for (float k1 = 1.0f; k1 <= 2.0f; k1 += 0.0025f) {
                double e = 0.0;
                for (int i = 0; i < kAngles; ++i) {
                    const float x = glm::radians(static_cast<float>(i)) / k1;
                    const double v = 1.0 / std::sqrt(1.0 + std::pow(x, k2)) - target[i][c];
                    e += v * v;
                }
                if (e < best_c) best_c = e, best_k1 = k1;
            }
            f.k1_rad[c] = best_k1;
            total += best_c;
        }
        if (total < best_err) best_err = total, best = f;
    }
    return best;
}

ProductionAtmosphere::ProductionAtmosphere(AtmosphereParameters params, ProductionQuality quality,
                                           const TableCacheOptions& cache)
    : params_(std::move(params)), quality_(std::move(quality)) {
    const bool six = quality_.sky_view && quality_.sky_view_wavelengths == 6;
    if (six) {
        const std::vector<double> grid = sky_view_wavelength_grid();
        const auto triplet = [](const double* l) { return glm::dvec3(l[0], l[1], l[2]); };
        gpu_ = to_shader_params(params_, triplet(kProductionWavelengths), grid);
        gpu2_ = to_shader_params(params_, triplet(kProductionWavelengths2), grid);
    } else {
        gpu_ = to_shader_params(params_);
    }
    color_weights_ = production_color_weights(params_);
    if (quality_.analytic) fit_ = fit_analytic_sun(gpu_);
    tables_ = load_or_build_tables(params_, gpu_, quality_, cache);
    if (six) tables2_ = load_or_build_tables(params_, gpu2_, quality_, cache, "610-500-400");
}

vec3 ProductionAtmosphere::radiance(const AtmosphereRayStart& st, float t_geometry, vec3* transmittance) const {
    return radiance(st, t_geometry, transmittance,
                    eclipse_ray(eclipse_no_casters(), vec2(1.0f), vec3(0.0f), vec3(0.0f)));
}

vec3 ProductionAtmosphere::radiance(const AtmosphereRayStart& st, float t_geometry, vec3* transmittance,
                                    EclipseRay shadow) const {
    const RadianceParts parts = radiance_parts(st, t_geometry, transmittance, shadow);
    return parts.air + gpu_.ground_albedo * parts.ground_per_albedo;
}

ProductionAtmosphere::RadianceParts ProductionAtmosphere::radiance_parts(const AtmosphereRayStart& st) const {
    return radiance_parts(st, -1.0f, nullptr, eclipse_ray(eclipse_no_casters(), vec2(1.0f), vec3(0.0f), vec3(0.0f)));
}

ProductionAtmosphere::RadianceParts ProductionAtmosphere::radiance_parts(const AtmosphereRayStart& st, float t_geometry,
                                                                         vec3* transmittance, EclipseRay shadow) const {
    if (shadow.casters.mode == ECLIPSE_MODE_LUT || shadow.casters.mode == ECLIPSE_MODE_ILLUSTRATIVE)
        shadow.casters.mode = ECLIPSE_MODE_EXACT;
    const sampler2D no_lut{&tables_.transmittance};  // never sampled in exact or fast mode
    const AtmosphereParams& a = gpu_;
    const sampler2D trans{&tables_.transmittance}, ms{&tables_.multiple_scattering}, irr{&tables_.irradiance};
    const vec2 ts(tables_.transmittance.width, tables_.transmittance.height);
    const vec2 mss(tables_.multiple_scattering.width, tables_.multiple_scattering.height);
    const vec2 es(tables_.irradiance.width, tables_.irradiance.height);
    const bool ground = st.valid && atm_ray_hits_ground(a, st.r_m, st.mu);
    const bool geometry_first = t_geometry >= 0.0f && (!ground || t_geometry < atm_ground_distance(a, st));
    AtmosphereSegment seg;
    if (quality_.analytic) {
        seg = atm_analytic_view_ray(a, fit_, st, t_geometry);
        seg.inscatter_per_sr =
            seg.inscatter_per_sr * eclipse_light_along(shadow, no_lut, 0.5f * atm_view_ray_length(a, st, t_geometry));
    } else {
        seg = atm_view_ray_shadowed(a, trans, ts, ms, mss, quality_.multiple_scattering, st, t_geometry,
                                    quality_.view_samples, shadow, no_lut);
    }
    RadianceParts out;
    out.air = seg.inscatter_per_sr;
    if (ground && !geometry_first) {
        vec3 surface;  // per unit albedo
        if (quality_.analytic) {
            const float t = atm_distance_to_ground(a, st.r_m, st.mu);
            const float mu_s_g = atm_mu_s_at(st.r_m, st.mu_s, st.nu, t, a.bottom_radius_m);
            surface = vec3(1.0f / CUPOLA_PI) * atm_analytic_sun(fit_, mu_s_g) * std::max(mu_s_g, 0.0f);
        } else {
            surface = atm_ground_radiance(a, trans, ts, irr, es, st, vec3(1.0f));
        }
        out.ground_per_albedo =
            seg.transmittance * surface * eclipse_light_along(shadow, no_lut, atm_distance_to_ground(a, st.r_m, st.mu));
    }
    if (transmittance) *transmittance = seg.transmittance;
    return out;
}

glm::dvec3 ProductionAtmosphere::to_xyz(const vec3& f) const {
    return glm::dvec3(atm_samples_to_xyz(f, sampler2D{&color_weights_}, static_cast<float>(color_weights_.width)));
}

const SkyViewTable& ProductionAtmosphere::sky_view_table(float d_m, float mu_s) const {
    std::lock_guard<std::mutex> lock(sky_view_cache_->mutex);
    auto& slot = sky_view_cache_->tables[{d_m, mu_s}];
    if (!slot) slot = std::make_unique<SkyViewTable>(build_sky_view_table(*this, d_m, mu_s));
    return *slot;
}

glm::dvec3 linear_srgb_to_xyz(const glm::dvec3& rgb) {
    static const glm::dmat3 inverse = glm::inverse(
        glm::transpose(glm::dmat3(3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570)));
    return inverse * rgb;
}

// A sky query the way the GPU's look-up pass answers it (shaders/atmosphere_lookup.frag): the
// in-scatter from the table, plus the ground's albedo times the table's white-ground radiance.
ProductionRadiance ProductionAtmosphere::sky_from_table(const AtmosphereRayStart& st, float d_m, const vec3& v,
                                                        const vec3& sun) const {
    ProductionRadiance out;
    out.in_atmosphere = st.valid;
    if (!st.valid) return out;
    const vec3 c_hat(0.0f, 0.0f, -1.0f);
    // The table the GPU draws with: the Sun's zenith angle on its grid (sky_view_table_sun_mu).
    const SkyViewTable& t = sky_view_table(d_m, sky_view_table_sun_mu(-dot(sun, c_hat)));
    const bool ground = atm_ray_hits_ground(gpu_, st.r_m, st.mu);
    const vec2 uv = atm_sky_view_pixel_uv(gpu_, d_m, v, c_hat, sun, st, ground, t.size());
    vec3 rgb = atm_sky_view_inscatter(gpu_, sampler2D{&t.parts[0]}, sampler2D{&t.parts[1]}, uv, st.nu);
    const vec3 third = vec3(textureLod(sampler2D{&t.parts[2]}, uv, 0.0));
    if (ground) rgb = rgb + gpu_.ground_albedo * third;
    out.rgb = glm::dvec3(rgb);
    out.xyz = linear_srgb_to_xyz(out.rgb);
    out.luminance = out.xyz.y;
    out.transmittance = ground ? glm::dvec3(0.0) : glm::dvec3(third);
    out.hits_ground = ground;
    return out;
}

ProductionRadiance ProductionAtmosphere::sky(const SkyQuery& q) const {
    const double d = params_.bottom_radius + std::max(q.altitude_m, kMinCameraAltitude);
    const double tv = glm::radians(q.view_zenith_deg), ts = glm::radians(q.sun_zenith_deg);
    const double az = glm::radians(q.relative_azimuth_deg);
    // Local frame at the camera: z up (away from the centre), the view in the x-z plane.
    const vec3 v(static_cast<float>(std::sin(tv)), 0.0f, static_cast<float>(std::cos(tv)));
    const vec3 sun(static_cast<float>(std::sin(ts) * std::cos(az)), static_cast<float>(std::sin(ts) * std::sin(az)),
                   static_cast<float>(std::cos(ts)));
    const AtmosphereRayStart st = atm_ray_start(gpu_, static_cast<float>(d), v, vec3(0.0f, 0.0f, -1.0f), sun);
    if (quality_.sky_view) return sky_from_table(st, static_cast<float>(d), v, sun);
    ProductionRadiance out;
    vec3 t;
    const vec3 f = radiance(st, -1.0f, &t);
    out.xyz = to_xyz(f);
    out.rgb = xyz_to_linear_srgb(out.xyz);
    out.luminance = out.xyz.y;
    out.transmittance = glm::dvec3(t);
    out.in_atmosphere = st.valid;
    out.hits_ground = st.valid && atm_ray_hits_ground(gpu_, st.r_m, st.mu);
    return out;
}

}  // namespace cupola::atmosphere
