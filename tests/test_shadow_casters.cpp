// Caster selection on the CPU (Ekelin & Fernqvist 2009, sections 3.3.1 and 3.3.3): shadow groups
// (parent/child, siblings only when allowed), the penumbra-reaches-receiver test against
// brute-force sampling of the visible fraction, per-frame selection on the real ephemeris, the
// shader input it builds, and the scene/show file errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "config/config_error.hpp"
#include "eclipse/eclipse_reference.hpp"
#include "eclipse/shadow_casters.hpp"
#include "scene/ephemeris.hpp"
#include "scene/sim_time.hpp"
#include "show_script.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

nlohmann::json body(const std::string& name, const std::string& kind, const std::string& eph, double r) {
    return {{"name", name}, {"kind", kind}, {"ephemeris", eph}, {"radius_m", r}, {"texture", "generated:" + name}};
}

nlohmann::json saturn_like_scene(bool siblings) {
    return {{"bodies",
             {body("sun", "star", "sun", 6.957e8), body("saturn", "planet", "saturn", 5.8e7),
              body("titan", "moon", "moon", 2.5e6), body("dione", "moon", "moon", 5.6e5),
              body("enceladus", "moon", "moon", 2.5e5)}},
            {"shadows",
             {{"groups",
               {{{"parent", "saturn"},
                 {"children", {"titan", "dione", "enceladus"}},
                 {"siblings_shadow_each_other", siblings}}}}}},
            {"stars", {{"catalog", test::source_path("data/stars/bright_stars.csv")}}}};
}

SceneConfig load(const std::string& name, const nlohmann::json& j) {
    const std::string dir = test::scratch_dir("ShadowCasters_" + name);
    test::write_text(dir + "/scene.json", j.dump(2));
    return load_scene_config(dir + "/scene.json");
}

void expect_scene_error(const std::string& name, const nlohmann::json& j, const std::string& field,
                        const std::string& words) {
    try {
        load(name, j);
        FAIL() << "expected an error naming " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}

}  // namespace

TEST(ShadowGroups, ParentAndChildrenShadowEachOtherSiblingsOnlyWhenAllowed) {
    const SceneConfig s = load("groups", saturn_like_scene(false));
    const auto c = shadow_candidates(s);
    const uint16_t saturn = s.find("saturn")->id, titan = s.find("titan")->id, dione = s.find("dione")->id,
                   enceladus = s.find("enceladus")->id;
    EXPECT_EQ(c[saturn], (std::vector<uint16_t>{titan, dione, enceladus}));  // three shadows on the parent
    EXPECT_EQ(c[titan], std::vector<uint16_t>{saturn});                      // one on each child
    EXPECT_EQ(c[dione], std::vector<uint16_t>{saturn});
    EXPECT_TRUE(c[s.find("sun")->id].empty());

    const SceneConfig all = load("groups_siblings", saturn_like_scene(true));
    const auto d = shadow_candidates(all);
    EXPECT_EQ(d[titan], (std::vector<uint16_t>{saturn, dione, enceladus}));
    EXPECT_EQ(d[saturn].size(), 3u);
}

// The cheap cone test never drops a receiver that a real shadow touches (checked against the
// visible fraction sampled over the receiver's sphere), and drops clear misses.
TEST(PenumbraReaches, AgreesWithSampledVisibleFraction) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const glm::dvec3 sun(0.0);
    const double rs = 6.96e8, rc = 1.7374e6, rr = 6.371e6;
    int reached = 0, missed = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const glm::dvec3 caster(1.496e11, 0.0, 0.0);
        // Receivers around the caster's shadow, 0.3 to 1.5 million km behind it, offsets up to 30 000 km.
        const glm::dvec3 receiver =
            caster + glm::dvec3(3.0e8 + 1.2e9 * (0.5 + 0.5 * u(rng)), 3.0e7 * u(rng), 3.0e7 * u(rng));
        const bool test = penumbra_reaches(sun, rs, caster, rc, receiver, rr);
        // Brute force: does any point of the receiver's sphere see the Sun partly hidden?
        bool shadowed = false;
        for (int k = 0; k < 4000 && !shadowed; ++k) {
            glm::dvec3 n(u(rng), u(rng), u(rng));
            if (glm::length(n) < 1e-3) continue;
            const glm::dvec3 p = receiver + glm::normalize(n) * rr;
            const glm::dvec3 us = glm::normalize(sun - p), uc = glm::normalize(caster - p);
            const double a_s = std::asin(rs / glm::length(sun - p)), a_c = std::asin(rc / glm::length(caster - p));
            shadowed = 2.0 * std::asin(0.5 * glm::length(us - uc)) < a_s + a_c;
        }
        if (shadowed) {
            EXPECT_TRUE(test) << "trial " << trial << ": a shadowed receiver was dropped";
        }
        (test ? reached : missed) += 1;
    }
    EXPECT_GT(reached, 20);
    EXPECT_GT(missed, 20);
    // The Sun's side of the caster is never shadowed; nor a receiver far off the axis.
    EXPECT_FALSE(penumbra_reaches(sun, rs, glm::dvec3(1.496e11, 0, 0), rc, glm::dvec3(1.4e11, 0, 0), rr));
    EXPECT_FALSE(penumbra_reaches(sun, rs, glm::dvec3(1.496e11, 0, 0), rc, glm::dvec3(1.5e11, 1e9, 0), rr));
}

// One set of mode numbers: the scene file's names, ShadowMode, the frame flags and the shaders'
// ECLIPSE_MODE_* agree, and every mode survives the trip through RenderSettings::flags.
TEST(ShadowCasting, ModeNumbersAreTheShadersOwn) {
    const std::vector<std::pair<std::string, int>> modes = {{"exact", shading::ECLIPSE_MODE_EXACT},
                                                            {"fast", shading::ECLIPSE_MODE_FAST},
                                                            {"lut", shading::ECLIPSE_MODE_LUT},
                                                            {"illustrative", shading::ECLIPSE_MODE_ILLUSTRATIVE},
                                                            {"off", shading::ECLIPSE_MODE_OFF}};
    ASSERT_EQ(shadow_mode_names().size(), modes.size());
    for (const auto& [name, number] : modes) {
        const ShadowMode m = shadow_mode_from_name(name);
        EXPECT_EQ(static_cast<int>(m), number) << name;
        EXPECT_EQ(shadow_mode_of(with_shadow_mode(0xfff0u, m)), m) << name;
        EXPECT_EQ(with_shadow_mode(0xfff0u, m) & ~kShadowModeMask, 0xfff0u) << name;
    }
}

// On the real sky: the Moon shadows the Earth during the 2006-03-29 eclipse and not a week
// later; the Earth shadows the Moon in the 2022-11-08 lunar eclipse. The shader input holds the
// casters relative to the receiver's centre, in double then float.
TEST(ShadowCasting, SelectsTheMoonOnlyDuringTheEclipse) {
    const SceneConfig s = load_scene_config(test::source_path("configs/scenes/earth-physical.json"));
    const uint16_t earth = s.find("earth")->id, moon = s.find("moon")->id;
    ShadowCasting casting(s, {{earth, glm::vec3(0.1f, 0.01f, 0.001f)}});
    auto snap_at = [&](const std::string& utc, ShadowMode mode) {
        Snapshot snap;
        snap.sim_time_s = utc_iso_to_j2000_seconds(utc);
        for (const auto& b : s.bodies) snap.bodies.push_back(body_state(b, snap.sim_time_s));
        snap.settings.flags = with_shadow_mode(0, mode);
        return snap;
    };
    const Snapshot solar = snap_at("2006-03-29T10:11:00Z", ShadowMode::Exact);
    EXPECT_EQ(casting.active_casters(solar, earth), std::vector<uint16_t>{moon});
    EXPECT_TRUE(casting.active_casters(solar, moon).empty());
    EXPECT_TRUE(casting.active_casters(snap_at("2006-04-05T10:00:00Z", ShadowMode::Exact), earth).empty());
    EXPECT_TRUE(casting.active_casters(snap_at("2006-03-29T10:11:00Z", ShadowMode::Off), earth).empty());

    const Snapshot lunar = snap_at("2022-11-08T10:59:00Z", ShadowMode::Lookup);
    EXPECT_EQ(casting.active_casters(lunar, moon), std::vector<uint16_t>{earth});
    const shading::EclipseCasters e = casting.casters_for(lunar, moon, glm::dmat3(1.0));
    ASSERT_EQ(e.count, 1);
    EXPECT_EQ(e.mode, static_cast<int>(ShadowMode::Lookup));
    EXPECT_FLOAT_EQ(e.caster_radius_m[0], static_cast<float>(s.find("earth")->radius_m));
    EXPECT_EQ(e.umbra_light[0], glm::vec3(0.1f, 0.01f, 0.001f));
    const glm::dvec3 rel = body_state(*s.find("earth"), lunar.sim_time_s).position_m -
                           body_state(*s.find("moon"), lunar.sim_time_s).position_m;
    EXPECT_NEAR(glm::length(glm::dvec3(e.caster_position_m[0]) - rel), 0.0, 1e-6 * glm::length(rel));
    EXPECT_FLOAT_EQ(e.sun_radius_m, static_cast<float>(s.find("sun")->radius_m));
}

TEST(ShadowConfig, ErrorsNameTheField) {
    auto j = saturn_like_scene(false);
    j["shadows"]["groups"][0]["parent"] = "pluto";
    expect_scene_error("bad_parent", j, "shadows.groups[0].parent", "no body named \"pluto\"");
    j = saturn_like_scene(false);
    j["shadows"]["groups"][0]["children"] = {"sun"};
    expect_scene_error("star_child", j, "shadows.groups[0].children", "is a star");
    j = saturn_like_scene(false);
    j["shadows"]["groups"][0]["children"] = {"saturn"};
    expect_scene_error("self_child", j, "shadows.groups[0].children", "the group's parent");
    j = saturn_like_scene(false);
    j["shadows"]["mode"] = "soft";
    expect_scene_error("bad_mode", j, "shadows.mode", "soft");
    j = saturn_like_scene(false);
    j["bodies"][2]["umbra_light"] = {0.5, 2.0, 0.1};
    expect_scene_error("bad_umbra", j, "bodies[2].umbra_light", "[0, 1]");
}

TEST(ShowScript, ObserverOnTheGroundAndShadowModeSwitches) {
    const SceneConfig s = load_scene_config(test::source_path("configs/scenes/earth-physical.json"));
    const std::string dir = test::scratch_dir("ShadowCasters_show");
    const nlohmann::json show = {{"frame_interval_s", 1.0},
                                 {"keyframes",
                                  {{{"at_s", 0},
                                    {"time_utc", "2006-03-29T10:11:00Z"},
                                    {"camera",
                                     {{"anchor", "earth"},
                                      {"observer", {{"lat_deg", 23.15}, {"lon_deg", 16.73}, {"alt_m", 100}}},
                                      {"look_azimuth_deg", 90}}}},
                                   {{"at_s", 1},
                                    {"time_utc", "2006-03-29T10:11:01Z"},
                                    {"shadow_mode", "illustrative"},
                                    {"camera",
                                     {{"anchor", "earth"},
                                      {"observer", {{"lat_deg", 23.15}, {"lon_deg", 16.73}, {"alt_m", 100}}},
                                      {"look_at", "sun"}}}}}}};
    test::write_text(dir + "/show.json", show.dump(2));
    const ShowScript script = ShowScript::load(dir + "/show.json", s);
    const Snapshot a = script.evaluate(0.0, s), b = script.evaluate(1.0, s);
    EXPECT_EQ(shadow_mode_of(a.settings.flags), s.shadows.mode);
    EXPECT_EQ(shadow_mode_of(b.settings.flags), ShadowMode::Illustrative);
    // Standing 100 m above the rendered sphere, at the site's geodetic direction.
    const glm::dvec3 e = a.bodies[s.find("earth")->id].position_m;
    EXPECT_NEAR(glm::length(a.camera_position_m - e), s.find("earth")->radius_m + 100.0, 1e-3);
    const glm::dvec3 itrs = glm::transpose(glm::mat3_cast(a.bodies[s.find("earth")->id].orientation)) *
                            glm::normalize(a.camera_position_m - e);
    EXPECT_NEAR(glm::degrees(std::atan2(itrs.y, itrs.x)), 16.73, 1e-6);
    // The camera's up (the dome's apex) is the zenith; facing east (azimuth 90) at the horizon.
    const glm::dmat3 cam = glm::mat3_cast(a.camera_orientation);
    const glm::dvec3 zenith = glm::normalize(a.camera_position_m - e);
    EXPECT_NEAR(glm::dot(cam[1], zenith), 1.0, 1e-9);
    const glm::dvec3 pole = glm::mat3_cast(a.bodies[s.find("earth")->id].orientation) * glm::dvec3(0, 0, 1);
    EXPECT_NEAR(glm::dot(-cam[2], glm::normalize(glm::cross(pole, zenith))), 1.0, 1e-6);  // east

    nlohmann::json bad = show;
    bad["keyframes"][0]["camera"]["offset_m"] = {1, 2, 3};
    test::write_text(dir + "/bad.json", bad.dump());
    EXPECT_THROW(ShowScript::load(dir + "/bad.json", s), ConfigError);
    bad = show;
    bad["keyframes"][1]["shadow_mode"] = "dark";
    test::write_text(dir + "/bad2.json", bad.dump());
    try {
        ShowScript::load(dir + "/bad2.json", s);
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("keyframes[1].shadow_mode"), std::string::npos) << e.what();
    }
}
