// The renderer's pass list (slave/scene_renderer.cpp, slave/passes/render_pass.hpp) on a real
// headless EGL context (llvmpipe on CI): a pass put into the list runs in its place, its output
// goes through the passes after it, and the targets follow from what it declares it reads and
// writes. The test pass adds a constant colour, either by sampling the colour so far (so the
// renderer must ping-pong) or by additive blending in place. The scene: a planet with an
// atmosphere seen from 0.1 radii above its ground, the channel centred on the air over its limb,
// and an airless moon beside it in empty space; the Sun behind the camera.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/render_pass.hpp"
#include "scene_renderer.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

constexpr double kAu = 1.495978707e11;
constexpr double kEarthRadius = 6.371e6;
constexpr double kMoonRadius = 2.6e5, kMoonDistance = 1.0e7;
constexpr double kMoonOffsetRad = 2.5 * std::numbers::pi / 180.0;  // right of the view centre
constexpr uint16_t kSun = 0, kEarth = 1, kMoon = 2;
const glm::vec3 kAdd(0.25f, 0.5f, 1.0f);

EglContext& context() { return test::headless_gl("RenderPasses"); }

SceneConfig make_scene(bool glare) {
    // One folder per test case: ctest runs the cases as parallel processes, and a shared folder,
    // emptied as each starts, could lose one case's files to another's start.
    const std::string dir = test::scratch_dir(std::string(glare ? "RenderPasses_glare_" : "RenderPasses_") +
                                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
    for (int i = 0; i < 8; ++i) hdr += std::string("\x80\x80\x80\x81", 4);  // RGBE 1.0
    test::write_text(dir + "/white.hdr", hdr);
    test::write_text(dir + "/stars.csv", "ra_deg,dec_deg,vmag,bv,name\n10.0,10.0,5.0,0.6,Faint\n");
    std::string json = R"({ "bodies": [
        { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 5.8e4,
          "limb_darkening_u": 0.6 },
        { "name": "earth", "kind": "planet", "ephemeris": "earth", "radius_m": 6.371e6, "texture": "white.hdr",
          "albedo": 0.3, "atmosphere": { "preset": "earth", "model": "analytic" } },
        { "name": "moon", "kind": "moon", "ephemeris": "moon", "radius_m": 2.6e5, "texture": "white.hdr",
          "albedo": 0.5 } ],
      "stars": { "catalog": "stars.csv", "magnitude_limit": -2.0 })";
    json += glare ? R"(, "glare": { "enabled": true } })" : " }";
    test::write_text(dir + "/scene.json", json);
    return load_scene_config(dir + "/scene.json");
}

// Adds kAdd to the colour so far. sample: reads the colour and writes the sum (the renderer must
// give it the other colour target); else writes kAdd with additive blending into the colour.
class AddConstantPass : public RenderPass {
public:
    explicit AddConstantPass(bool sample)
        : sample_(sample), program_("tests/fullscreen.vert", "tests/add_constant.frag") {}
    std::string name() const override { return sample_ ? "add constant (sampled)" : "add constant (blended)"; }
    PassIo io() const override { return {.reads_color = sample_, .writes_color = true}; }
    int prepare(const FrameContext& frame) override {
        ++prepared;
        seen_frame = frame.snap->frame;
        return 1;
    }
    void draw(const PassInputs& in, int step) override {
        EXPECT_EQ(step, 0);
        EXPECT_EQ(in.color != nullptr, sample_);
        EXPECT_EQ(in.geometry, nullptr);
        program_.use();
        program_.set("u_add", kAdd);
        program_.set("u_sample", sample_ ? 1 : 0);
        program_.set("u_scene", 0);
        if (sample_) {
            in.color->bind(0);
        } else {
            glEnablei(GL_BLEND, 0);
            glBlendFunci(0, GL_ONE, GL_ONE);
        }
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (!sample_) glDisablei(GL_BLEND, 0);
        gl::check("add constant pass");
        ++drawn;
    }

    int prepared = 0, drawn = 0;
    uint64_t seen_frame = 0;

private:
    bool sample_;
    GlProgram program_;
    GlEmptyVertexArray vao_;
};

// The view: the camera at the origin with the identity orientation (channel frame = world frame,
// -Z forward, +X right); the planet's centre to the left of the view centre by the angle of the
// middle of its air ring, the moon to the right in empty space, the Sun behind the camera.
struct View {
    SceneConfig scene;
    ClusterConfig cluster;
    ChannelConfig channel;
    Snapshot snap;
    double planet_distance_m = 1.1 * kEarthRadius;
    double ground_rad = 0.0, top_rad = 0.0, moon_rad = 0.0;  // angular radii
    glm::dvec3 planet_dir{0.0}, moon_dir{0.0};

    explicit View(bool glare = false) : scene(make_scene(glare)) {
        channel.name = "test";
        channel.width = channel.height = 64;
        channel.fov = FovDeg{4, 4, 4, 4};
        cluster.channels = {channel};
        ground_rad = std::asin(kEarthRadius / planet_distance_m);
        top_rad = std::asin(scene.bodies[kEarth].atmosphere.parameters.top_radius / planet_distance_m);
        moon_rad = std::asin(kMoonRadius / kMoonDistance);
        const double planet_off = 0.5 * (ground_rad + top_rad);
        planet_dir = glm::dvec3(-std::sin(planet_off), 0.0, -std::cos(planet_off));
        moon_dir = glm::dvec3(std::sin(kMoonOffsetRad), 0.0, -std::cos(kMoonOffsetRad));
        snap.frame = 7;
        snap.settings.exposure = 1.0f;
        snap.bodies = {BodyState{kSun, glm::dvec3(0.0, 0.0, kAu), {1, 0, 0, 0}},
                       BodyState{kEarth, planet_distance_m * planet_dir, {1, 0, 0, 0}},
                       BodyState{kMoon, kMoonDistance * moon_dir, {1, 0, 0, 0}}};
    }

    // Unit direction through the centre of image pixel (x, y), row 0 at the top.
    glm::dvec3 ray(int x, int y) const {
        const ChannelFrustum f = channel.frustum();
        const double tx = -f.tan_left() + (x + 0.5) / channel.width * (f.tan_left() + f.tan_right());
        const double ty = -f.tan_down() + (channel.height - 1 - y + 0.5) / channel.height * (f.tan_down() + f.tan_up());
        return glm::normalize(glm::dvec3(tx, ty, -1.0));
    }
};

// Where a pixel's ray goes, two pixels clear of every edge (else Edge).
enum class Region { Ground, Air, Space, Moon, Edge };

Region region(const View& v, int x, int y) {
    const double margin = 2.0 * glm::radians(8.0) / v.channel.width;
    const glm::dvec3 d = v.ray(x, y);
    const double to_planet = std::acos(glm::dot(d, v.planet_dir));
    const double to_moon = std::acos(glm::dot(d, v.moon_dir));
    if (to_moon < v.moon_rad - margin) return Region::Moon;
    if (to_moon < v.moon_rad + margin) return Region::Edge;
    if (to_planet < v.ground_rad - margin) return Region::Ground;
    if (to_planet > v.ground_rad + margin && to_planet < v.top_rad - margin) return Region::Air;
    if (to_planet > v.top_rad + margin) return Region::Space;
    return Region::Edge;
}

// What adding kAdd before some pass makes of a pixel, per region: exactly kAdd (nothing after
// it changes the pixel's colour from what it was), exactly nothing (a later pass overwrites it),
// or attenuated (the air dims what lies behind it: between nothing and kAdd).
enum class Effect { Added, None, Attenuated };

struct Prediction {
    Effect ground, air, space, moon;
};

struct Counts {
    int ground = 0, air = 0, space = 0, moon = 0;
    int air_dimmed = 0;  // air pixels where some component gained less than 90 % of kAdd
};

void expect_effect(const View& v, const Image& plain, const Image& with, const Prediction& want, Counts& n) {
    for (int y = 0; y < plain.height; ++y)
        for (int x = 0; x < plain.width; ++x) {
            const Region r = region(v, x, y);
            if (r == Region::Edge) continue;
            const Effect e = r == Region::Ground ? want.ground
                             : r == Region::Air  ? want.air
                             : r == Region::Moon ? want.moon
                                                 : want.space;
            (r == Region::Ground ? n.ground : r == Region::Air ? n.air : r == Region::Moon ? n.moon : n.space)++;
            const float* a = plain.pixel(x, y);
            const float* b = with.pixel(x, y);
            ASSERT_EQ(b[3], a[3]) << "alpha at " << x << "," << y;
            bool dimmed = false;
            for (int c = 0; c < 3; ++c) {
                const double diff = double(b[c]) - double(a[c]);
                const double tol = 1e-5 * (1.0 + std::abs(a[c]));
                if (e == Effect::Added) {
                    ASSERT_NEAR(diff, kAdd[c], tol) << "pixel " << x << "," << y << " c" << c;
                } else if (e == Effect::None) {
                    ASSERT_NEAR(diff, 0.0, tol) << "pixel " << x << "," << y << " c" << c;
                } else {
                    ASSERT_GE(diff, -tol) << "pixel " << x << "," << y << " c" << c;
                    ASSERT_LE(diff, kAdd[c] + tol) << "pixel " << x << "," << y << " c" << c;
                    dimmed = dimmed || diff < 0.9 * kAdd[c];
                }
            }
            n.air_dimmed += dimmed;
        }
}

size_t position_of(const SceneRenderer& r, const std::string& name) {
    const auto names = r.pass_names();
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return i;
    ADD_FAILURE() << "no pass \"" << name << "\"";
    return names.size();
}

// Renders the view with the test pass put in before `before` ("" for last) and compares with the
// plain render.
void expect_inserted(bool sample, const std::string& before, const Prediction& want) {
    context();
    const View v;
    SceneRenderer plain(v.cluster, v.channel, v.scene);
    const Image reference = plain.render(v.snap);
    SceneRenderer r(v.cluster, v.channel, v.scene);
    auto owned = std::make_unique<AddConstantPass>(sample);
    AddConstantPass* pass = owned.get();
    const size_t at = before.empty() ? r.pass_names().size() : position_of(r, before);
    r.insert_pass(at, std::move(owned));
    ASSERT_EQ(r.pass_names().at(at), pass->name());
    const Image img = r.render(v.snap);
    EXPECT_EQ(pass->prepared, 1);
    EXPECT_EQ(pass->drawn, 1);
    EXPECT_EQ(pass->seen_frame, v.snap.frame);
    EXPECT_EQ(r.atmosphere_stats().passes_run, 1);
    Counts n;
    expect_effect(v, reference, img, want, n);
    if (::testing::Test::HasFatalFailure()) return;
    ::testing::Test::RecordProperty("pixels_ground_air_space_moon",
                                    std::to_string(n.ground) + " " + std::to_string(n.air) + " " +
                                        std::to_string(n.space) + " " + std::to_string(n.moon));
    ::testing::Test::RecordProperty("air_dimmed", std::to_string(n.air_dimmed));
    // Every region is in the picture, so every prediction was checked.
    EXPECT_GT(n.ground, 100);
    EXPECT_GT(n.air, 50);
    EXPECT_GT(n.space, 100);
    EXPECT_GT(n.moon, 50);
    if (want.air == Effect::Attenuated) {
        EXPECT_GT(n.air_dimmed, n.air / 4) << "the air should dim what is behind it";
    }
    // A second frame runs the pass again, in the same place.
    const Image again = r.render(v.snap);
    EXPECT_EQ(pass->drawn, 2);
    EXPECT_EQ(again.rgba, img.rgba);
}

}  // namespace

TEST(RenderPasses, ThePipelineRunsInItsDocumentedOrder) {
    context();
    const View with_glare(true);
    EXPECT_EQ(SceneRenderer(with_glare.cluster, with_glare.channel, with_glare.scene).pass_names(),
              (std::vector<std::string>{"stars", "sun and bodies", "planet points", "glare probe", "glare halo",
                                        "atmosphere", "stars after the sky", "sun and bodies after the sky",
                                        "planet points after the sky", "glare", "alignment pattern"}));
    View airless;
    airless.scene.bodies[kEarth].atmosphere.present = false;
    EXPECT_EQ(SceneRenderer(airless.cluster, airless.channel, airless.scene).pass_names(),
              (std::vector<std::string>{"stars", "sun and bodies", "planet points", "alignment pattern"}));
}

// Before the atmosphere: the planet's surface is relit from the G-buffer (the constant is gone),
// the air dims it, the moon and empty space (their rays miss the air) keep it exactly.
TEST(RenderPasses, SampledPassBeforeTheAtmosphereIsDimmedByTheAir) {
    expect_inserted(true, "atmosphere", {Effect::None, Effect::Attenuated, Effect::Added, Effect::Added});
}
TEST(RenderPasses, BlendedPassBeforeTheAtmosphereIsDimmedByTheAir) {
    expect_inserted(false, "atmosphere", {Effect::None, Effect::Attenuated, Effect::Added, Effect::Added});
}

// Last: added everywhere, exactly.
TEST(RenderPasses, SampledPassLastAddsEverywhere) {
    expect_inserted(true, "", {Effect::Added, Effect::Added, Effect::Added, Effect::Added});
}
TEST(RenderPasses, BlendedPassLastAddsEverywhere) {
    expect_inserted(false, "", {Effect::Added, Effect::Added, Effect::Added, Effect::Added});
}

// Before the bodies: the opaque discs cover it (the moon too), the rest as before the atmosphere.
TEST(RenderPasses, BlendedPassBeforeTheBodiesIsCoveredByThem) {
    expect_inserted(false, "sun and bodies", {Effect::None, Effect::Attenuated, Effect::Added, Effect::None});
}

// A pass that reads the colour moves it to the other target; the G-buffer is attached with the
// first one only, so the bodies cannot follow it. The list refuses, names both and stays as it was.
TEST(RenderPasses, AnOrderTheTargetsCannotServeIsRefused) {
    context();
    const View v;
    SceneRenderer r(v.cluster, v.channel, v.scene);
    const auto before = r.pass_names();
    try {
        r.insert_pass(position_of(r, "sun and bodies"), std::make_unique<AddConstantPass>(true));
        FAIL() << "a colour reader before the G-buffer writer was accepted";
    } catch (const std::logic_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("\"sun and bodies\" writes the G-buffer after \"add constant (sampled)\""),
                  std::string::npos)
            << what;
    }
    EXPECT_EQ(r.pass_names(), before);
    EXPECT_THROW(r.insert_pass(before.size() + 1, std::make_unique<AddConstantPass>(false)), std::out_of_range);
    EXPECT_EQ(r.pass_names(), before);
    // Still renders as before.
    SceneRenderer plain(v.cluster, v.channel, v.scene);
    EXPECT_EQ(r.render(v.snap).rgba, plain.render(v.snap).rgba);
}
