#pragma once
// Which sources get a glare this frame, how bright they are at the camera, and how much of each
// spherical occluders hide (the analytic visibility every snapshot starts from; the measured
// one replaces it when the whole cluster reported, common/glare/glare_sharing).
//   - Stars of the scene (the Sun): always, irradiance = disc radiance x pi sin^2(alpha) x
//     limb-darkened mean.
//   - Planets and moons smaller than kMaxBodyRadius: Lambert spheres lit by the Sun, (2/3) albedo E_sun (R/d)^2
//   Phi(phase).
//   - Catalogue stars brighter than V = 2: zero_mag_flux x 10^(-0.4 V), coloured by B-V, times
//     how much of the star the eye sees against the sky behind it
//     (SceneAtmospheres::star_sky_weight; not while an airless body hides part of the Sun).
// Each is dimmed by the air in front of it (SceneAtmospheres::transmittance). A non-star source
// counts once its glare one degree away would reach glare.min_display on the dome, fading in up
// to twice that so nothing pops; the Suns first, then by brightness, at most max_sources.
#include <memory>
#include <vector>

#include "atmosphere/scene_atmospheres.hpp"
#include "config/scene_config.hpp"
#include "scene/star_catalog.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class GlareSources {
public:
    // atmospheres: may be nullptr (no dimming); not owned.
    GlareSources(const SceneConfig& scene, const SceneAtmospheres* atmospheres);

    // The frame's sources with their analytic visibility (GlareOrigin::Analytic). Needs the
    // snapshot's exposure (for the threshold).
    std::vector<GlareSource> select(const Snapshot& snap) const;

    // The glare's display value one degree from a source of this irradiance (the threshold's
    // measure), for the scene's glare settings.
    double display_at_one_degree(const glm::dvec3& irradiance, double exposure) const;

    static constexpr double kCatalogMagnitudeLimit = 2.0;
    static constexpr double kMaxBodyRadius = 0.0175;  // planets and moons up to 1 degree across the radius

private:
    struct Candidate;  // a source with its rank, before the brightest max_sources are kept
    // Steps of select(): the scene's bodies (stars, planets, moons), then the catalogue stars.
    void add_body_candidates(const Snapshot& snap, std::vector<Candidate>& candidates) const;
    void add_catalog_candidates(const Snapshot& snap, std::vector<Candidate>& candidates) const;
    glm::dvec3 transmittance(const Snapshot& snap, const glm::dvec3& dir) const;  // 1 without atmospheres

    const SceneConfig* scene_;
    const SceneAtmospheres* atmospheres_;
    std::vector<Star> stars_;
};

}  // namespace cupola
