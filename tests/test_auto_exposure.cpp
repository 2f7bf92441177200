// Cluster-wide automatic exposure (common/atmosphere/auto_exposure): one value per frame, decided by the
// master from data every channel shares, following the sky from noon to night.
#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/auto_exposure.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "master_node.hpp"
#include "eclipse/shadow_casters.hpp"
#include "scene/eclipse_geometry.hpp"
#include "scene/night_sky.hpp"
#include "scene/sim_time.hpp"
#include "show_script.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {
struct Fixture {
    ClusterConfig cluster = load_cluster_config(test::source_path("configs/descent-1ch.json"));
    SceneConfig scene = load_scene_config(cluster.scene_file);
    ShowScript show = ShowScript::load(cluster.show_file, scene);
};

// The same snapshot with the Sun moved to `sun_zenith_deg` at the camera (in the plane of the
// camera's zenith and its current Sun direction).
Snapshot with_sun_at(const Snapshot& base, const SceneConfig& scene, double sun_zenith_deg) {
    Snapshot s = base;
    const auto earth = scene.find("earth")->id, sun = scene.find("sun")->id;
    const glm::dvec3 up = glm::normalize(s.camera_position_m - s.bodies[earth].position_m);
    glm::dvec3 toward = s.bodies[sun].position_m - s.camera_position_m;
    toward = glm::normalize(toward - glm::dot(toward, up) * up);
    const double z = glm::radians(sun_zenith_deg);
    s.bodies[sun].position_m = s.camera_position_m + 1.496e11 * (std::cos(z) * up + std::sin(z) * toward);
    return s;
}
}  // namespace

TEST(AutoExposure, FollowsTheSkyFromNoonToNight) {
    Fixture f;
    ASSERT_TRUE(f.cluster.output.auto_exposure.enabled);
    const AutoExposure ae(f.cluster, f.scene);
    const Snapshot ground = make_frame_snapshot(f.cluster, f.scene, f.show, 28);  // 1 km up, at sunset
    const double noon = ae.exposure(with_sun_at(ground, f.scene, 20.0));
    const double sunset = ae.exposure(with_sun_at(ground, f.scene, 88.0));
    const double night = ae.exposure(with_sun_at(ground, f.scene, 130.0));
    EXPECT_GT(sunset, 3.0 * noon);
    EXPECT_GT(night, 100.0 * sunset);
    EXPECT_DOUBLE_EQ(night, f.cluster.output.auto_exposure.max_exposure);  // a black sky: the clamp
    // Noon daylight over the ground is thousands of cd/m^2 in this physical scene: key / L, with
    // L the log-average of the view (the key is the configured one in daylight).
    const double mean = ae.metered_luminance(with_sun_at(ground, f.scene, 20.0));
    EXPECT_GT(mean, 1000.0);
    EXPECT_LT(mean, 50000.0);
    EXPECT_NEAR(noon, f.cluster.output.auto_exposure.key / mean, 1e-12 * noon);
}

TEST(AutoExposure, IsOneDeterministicValuePerFrameInTheSnapshot) {
    Fixture f;
    const AutoExposure ae(f.cluster, f.scene);
    for (uint64_t frame : {0u, 12u, 28u}) {
        const Snapshot a = make_frame_snapshot(f.cluster, f.scene, f.show, frame, &ae);
        const Snapshot b = make_frame_snapshot(f.cluster, f.scene, f.show, frame, &ae);
        EXPECT_EQ(a, b);  // recomputable from the show alone: no hidden state
        EXPECT_FLOAT_EQ(a.settings.exposure, static_cast<float>(ae.exposure(a)));
        EXPECT_GE(a.settings.exposure, f.cluster.output.auto_exposure.min_exposure);
        EXPECT_LE(a.settings.exposure, f.cluster.output.auto_exposure.max_exposure);
    }
    // Fixed exposure when auto exposure is off.
    f.cluster.output.auto_exposure.enabled = false;
    f.cluster.output.exposure = 0.25;
    const AutoExposure off(f.cluster, f.scene);
    EXPECT_FLOAT_EQ(make_frame_snapshot(f.cluster, f.scene, f.show, 5, &off).settings.exposure, 0.25f);
}

// Night vision is a switch of the eye's adaptation: in the snapshot's flags (every channel shows
// the same) only when configured and only under the automatic exposure.
TEST(AutoExposure, NightVisionTravelsInTheSnapshotOnlyWithTheEyesAdaptation) {
    Fixture f;
    const AutoExposure ae(f.cluster, f.scene);
    EXPECT_FALSE(night_vision_of(make_frame_snapshot(f.cluster, f.scene, f.show, 12, &ae).settings.flags));
    f.cluster.output.auto_exposure.night_vision = true;
    const AutoExposure night(f.cluster, f.scene);
    const Snapshot on = make_frame_snapshot(f.cluster, f.scene, f.show, 12, &night);
    EXPECT_TRUE(night_vision_of(on.settings.flags));
    EXPECT_FALSE(acuity_blur_of(on.settings.flags));
    EXPECT_GT(on.settings.adapted_cd_m2, 0.0f);
    f.cluster.output.auto_exposure.acuity_blur = true;  // the eye's acuity rides with its night vision
    const AutoExposure blur(f.cluster, f.scene);
    EXPECT_TRUE(acuity_blur_of(make_frame_snapshot(f.cluster, f.scene, f.show, 12, &blur).settings.flags));
    f.cluster.output.auto_exposure.night_vision = false;
    const AutoExposure blur_alone(f.cluster, f.scene);
    EXPECT_FALSE(acuity_blur_of(make_frame_snapshot(f.cluster, f.scene, f.show, 12, &blur_alone).settings.flags));
    f.cluster.output.auto_exposure.night_vision = true;
    f.cluster.output.auto_exposure.enabled = false;
    const AutoExposure fixed(f.cluster, f.scene);
    EXPECT_FALSE(night_vision_of(make_frame_snapshot(f.cluster, f.scene, f.show, 12, &fixed).settings.flags));
}

// The night sky's own glow is part of what the eye adapts to: a city sky (Bortle 8) is metered,
// not a black sky at the exposure's clamp.
TEST(AutoExposure, MetersTheNightSkysGlow) {
    Fixture f;
    const AutoExposure ae(f.cluster, f.scene);
    Snapshot night = with_sun_at(make_frame_snapshot(f.cluster, f.scene, f.show, 28), f.scene, 130.0);
    ShowSettings settings;
    Snapshot dark = night;
    finish_frame_snapshot(dark, settings, f.cluster, f.scene, 28, 0.5, &ae, nullptr);
    settings.sky_brightness = 18.0;
    finish_frame_snapshot(night, settings, f.cluster, f.scene, 28, 0.5, &ae, nullptr);
    const double zenith = sky_brightness_cd_m2(18.0);
    EXPECT_FLOAT_EQ(night.settings.night_sky_cd_m2, static_cast<float>(zenith));
    std::printf("city sky: adapted to %.3g cd/m^2 (zenith %.3g), exposure %.3g; black sky: exposure %.3g\n",
                night.settings.adapted_cd_m2, zenith, night.settings.exposure, dark.settings.exposure);
    EXPECT_GT(night.settings.adapted_cd_m2, 0.8 * zenith);  // brighter toward the horizon, less with height
    EXPECT_LT(night.settings.adapted_cd_m2, 2.5 * zenith);
    EXPECT_LT(night.settings.exposure, 0.1 * dark.settings.exposure);
}

// In totality the sky the exposure sees is shadowed too: the exposure opens up by orders of
// magnitude against the same frame with shadows off, and by about 1 / visible fraction at 90 %.
TEST(AutoExposure, OpensUpInTotality) {
    Fixture f;
    const EclipseEvent ev = next_solar_eclipse(utc_iso_to_j2000_seconds("2006-03-25T00:00:00Z"));
    ShowKeyframe k;
    k.sim_time_s = ev.peak_tt_s;
    k.camera.anchor = f.scene.find("earth")->id;
    k.camera.observer = ObserverSite{ev.lat_deg, ev.lon_deg, 2.0, 148.4, 0.0};
    Snapshot snap = ShowScript({k}, 1.0).evaluate(0.0, f.scene);
    const AutoExposure ae(f.cluster, f.scene);
    snap.settings.flags = with_shadow_mode(0, ShadowMode::Off);
    const double off = ae.metered_luminance(snap);
    snap.settings.flags = with_shadow_mode(0, ShadowMode::Exact);
    const double total = ae.metered_luminance(snap);
    std::printf("metered luminance at greatest eclipse: shadows off %.4g, exact %.4g\n", off, total);
    EXPECT_GT(off, 0.0);
    // What is metered in totality is the lit sky, the glow toward the horizon outside the
    // shadow (the dark sky by the Sun lies below 1 % of its highlight): 1.2e-3 of the uneclipsed sky.
    EXPECT_LT(total, 3e-3 * off);
    EXPECT_GT(ae.exposure(snap), 100.0 * f.cluster.output.auto_exposure.min_exposure);
}
