// The sky drawn first (slave/passes/beyond_the_air.hpp): from inside the air of the only
// atmosphere in view, the sky and the ground are written over the whole channel without a clear,
// and the stars, the Sun and the Moon are drawn after them, each taking the air in front of it
// from the sky-view table itself. On a real headless EGL context (llvmpipe on CI), the earth-moon
// scene gives the same image as with everything drawn before the sky (SceneRenderer::
// set_sky_first(false)), within float rounding; the stars within what one transmittance per star
// instead of one per pixel changes. Every pixel is written, the colour is not cleared, and from
// orbit or with a march level the usual order runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <glm/gtc/quaternion.hpp>

#include "atmosphere/auto_exposure.hpp"
#include "atmosphere/scene_atmospheres.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "glare/glare_sources.hpp"
#include "master_node.hpp"
#include "scene_renderer.hpp"
#include "show_script.hpp"
#include "support/earth_moon_scene.hpp"
#include "support/headless_gl.hpp"
#include "support/image_difference.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

EglContext& context() { return test::headless_gl("SkyFirst"); }

const SceneConfig& scene() { return test::earth_moon_scene(); }

// One square channel `half_fov_deg` each way from its centre.
ClusterConfig one_channel(double half_fov_deg, int size = 96) {
    ClusterConfig c;
    ChannelConfig ch;
    ch.name = "sky-first";
    ch.fov = FovDeg{half_fov_deg, half_fov_deg, half_fov_deg, half_fov_deg};
    ch.width = ch.height = size;
    c.channels = {ch};
    c.output.auto_exposure.enabled = true;
    return c;
}

glm::dvec3 local(double az_deg, double el_deg) { return test::horizon_direction(az_deg, el_deg); }

// Where the camera is and looks, and where the Sun and the Moon are (azimuth, elevation in the
// observer's horizon frame: the Earth at the origin, the camera on +z).
struct View {
    double altitude_m = 2.0;
    double look_az = 20.0, look_el = 20.0;
    double sun_az = 0.0, sun_el = 40.0;
    double moon_az = 60.0, moon_el = 15.0;
};

Snapshot snapshot(const ClusterConfig& cl, const View& v) {
    const SceneConfig& sc = scene();
    Snapshot s;
    s.bodies.resize(sc.bodies.size());
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    s.bodies[sc.find("sun")->id].position_m = 1.495978707e11 * local(v.sun_az, v.sun_el);
    const glm::dvec3 up(0, 0, 1);
    s.camera_position_m = (sc.find("earth")->radius_m + v.altitude_m) * up;
    // Seen from the camera there (the parallax from the Earth's centre is up to a degree).
    s.bodies[sc.find("moon")->id].position_m = s.camera_position_m + 3.844e8 * local(v.moon_az, v.moon_el);
    const glm::dvec3 fwd = local(v.look_az, v.look_el), right = glm::normalize(glm::cross(fwd, up));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(right, fwd), -fwd));
    static const SceneAtmospheres atmospheres(sc);
    const AutoExposure exposure(cl, sc, &atmospheres);  // keeps the cluster: one per call
    static const GlareSources glare(sc, &atmospheres);
    finish_frame_snapshot(s, ShowSettings{}, cl, sc, 1, 1.0 / 60.0, &exposure, &glare);
    return s;
}

struct Rendered {
    Image image;
    uint64_t color_clears = 0;
};

Rendered render(const ClusterConfig& cl, const Snapshot& s, bool sky_first, const SceneConfig& sc = scene()) {
    SceneRenderer r(cl, cl.channels[0], sc);
    r.set_sky_first(sky_first);
    Rendered out;
    out.image = r.render(s);
    out.color_clears = r.color_clears();
    return out;
}

using test::relative_difference;

double green_sum(const Image& img) {
    double sum = 0.0;
    for (size_t i = 1; i < img.rgba.size(); i += 4) sum += img.rgba[i];
    return sum;
}

// Both orders, the same view: the images agree within `tolerance` of the brightest value; only
// the sky-first one skips the colour clear, and its coverage (alpha) is 1 everywhere, as a
// cleared colour's is.
void expect_same_image(const ClusterConfig& cl, const View& v, float tolerance, Rendered* first_out = nullptr,
                       Rendered* last_out = nullptr) {
    context();
    const Snapshot s = snapshot(cl, v);
    const Rendered first = render(cl, s, true), last = render(cl, s, false);
    EXPECT_EQ(first.color_clears, 0u) << "the sky was not drawn first";
    EXPECT_EQ(last.color_clears, 1u);
    EXPECT_LE(relative_difference(last.image, first.image), tolerance);
    for (size_t i = 3; i < first.image.rgba.size(); i += 4) ASSERT_EQ(first.image.rgba[i], 1.0f) << "pixel " << i / 4;
    for (float c : first.image.rgba) ASSERT_TRUE(std::isfinite(c));
    if (first_out) *first_out = first;
    if (last_out) *last_out = last;
}

}  // namespace

TEST(SkyFirst, ByDayTheSameImageAsTheSkyDrawnLast) {
    expect_same_image(one_channel(45.0), View{}, 1e-5f);  // the ground, the Sun's glare, the Moon
}

TEST(SkyFirst, AtSunsetTheReddenedSunIsTheSame) {
    View v;
    v.sun_el = 1.0;
    v.look_az = 0.0;
    v.look_el = 1.0;
    expect_same_image(one_channel(2.0), v, 1e-5f);  // the disc, the corona, the air in front
}

TEST(SkyFirst, TheMoonThroughTheAirIsTheSameAndTheGroundHidesItsLowerHalf) {
    View v;  // a nearly full Moon 0.1 degree up at dusk: its disc (0.26 degree radius) crosses the horizon
    v.moon_az = v.look_az = 60.0;
    v.moon_el = v.look_el = 0.1;
    v.sun_az = 240.0;  // behind the camera, in twilight: the Moon's face is lit, the sky is dark
    v.sun_el = -12.0;
    const ClusterConfig cl = one_channel(1.0);
    Rendered first, last;
    expect_same_image(cl, v, 1e-5f, &first, &last);
    // Against the same view with the Moon behind the camera: above the horizon the Moon shows;
    // below it the ground covers the Moon: only the ground and the air in front of it, which the
    // Moon lights as well (the moonlit sky: brightest toward the Moon, so not the bare frame's),
    // far under the disc's light.
    View away = v;
    away.moon_az = v.look_az + 180.0;
    context();
    const Rendered bare = render(cl, snapshot(cl, away), true);
    const Image& with = first.image;
    const int cx = with.width / 2;
    // 96 rows over 2 degrees, row 0 at the top: 6 rows above the centre is 0.225 degrees up, on
    // the Moon; 9 rows below it 0.09 degrees down, on the Moon too but below the horizon (its dip
    // from 2 m is 0.045 degrees).
    const int above = with.height / 2 - 6, below = with.height / 2 + 9;
    std::printf("the Moon above the horizon %.3g, the ground below it %.3g\n", with.pixel(cx, above)[1],
                with.pixel(cx, below)[1]);
    EXPECT_GT(with.pixel(cx, above)[1], 2.0f * bare.image.pixel(cx, above)[1]);
    for (int x = 0; x < with.width; ++x) EXPECT_LT(with.pixel(x, below)[1], 1e-2f * with.pixel(cx, above)[1]) << x;
    // To look at (docs/images/sky-first-moonrise.png): CUPOLA_TEST_IMAGES=DIR writes both orders.
    if (const char* dir = std::getenv("CUPOLA_TEST_IMAGES")) {
        const double exposure = snapshot(cl, v).settings.exposure;
        FrameMetadata meta;
        meta.channel_name = "sky-first";
        write_frame(dir, first.image, meta, {"png"}, exposure);
        meta.channel_name = "sky-last";
        meta.frame = 1;
        write_frame(dir, last.image, meta, {"png"}, exposure);
    }
}

TEST(SkyFirst, AtNightTheStarsTakeTheAirInFrontOfThem) {
    View v;
    v.sun_el = -30.0;
    v.look_el = 35.0;
    v.moon_el = -20.0;
    const ClusterConfig cl = one_channel(30.0, 128);
    Rendered first, last;
    // One transmittance per star, not per pixel: within a few percent at the sprites' edges.
    expect_same_image(cl, v, 0.03f, &first, &last);
    const double first_sum = green_sum(first.image), last_sum = green_sum(last.image);
    EXPECT_NEAR(first_sum / last_sum, 1.0, 0.005);
    // And the air does dim them: without it (no atmosphere, so no sky at all) the stars are
    // brighter by far more than that.
    SceneConfig airless = scene();
    for (auto& b : airless.bodies) b.atmosphere.present = false;
    const Rendered bare = render(cl, snapshot(cl, v), true, airless);
    EXPECT_EQ(bare.color_clears, 1u);
    EXPECT_GT(green_sum(bare.image), 1.05 * first_sum);
}

TEST(SkyFirst, EveryPixelIsWrittenWithoutAClear) {
    context();
    const ClusterConfig cl = one_channel(45.0);
    View sunset;
    sunset.sun_el = 0.0;
    sunset.look_az = 180.0;
    const Snapshot day = snapshot(cl, View{}), other = snapshot(cl, sunset);
    // The colour target first holds another frame, drawn in the usual order; then the day, sky first.
    SceneRenderer r(cl, cl.channels[0], scene());
    r.set_sky_first(false);
    const Image before = r.render(other);
    r.set_sky_first(true);
    const Image after = r.render(day);
    EXPECT_EQ(r.color_clears(), 1u);
    const Image fresh = render(cl, day, true).image;
    ASSERT_NE(before.rgba, fresh.rgba);
    EXPECT_EQ(after.rgba, fresh.rgba);
}

TEST(SkyFirst, FromOrbitOrWithTheMarchTheUsualOrderRuns) {
    context();
    const ClusterConfig cl = one_channel(45.0);
    View orbit;
    orbit.altitude_m = 400.0e3;
    orbit.look_el = -15.0;
    EXPECT_EQ(render(cl, snapshot(cl, orbit), true).color_clears, 1u);
    SceneConfig marched = scene();
    for (auto& b : marched.bodies)
        if (b.atmosphere.present) b.atmosphere.model = "medium";
    EXPECT_EQ(render(cl, snapshot(cl, View{}), true, marched).color_clears, 1u);
}
