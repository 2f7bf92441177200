// Every config error names the file and the field; the shipped configs load.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "config/scene_config.hpp"
#include "input/device_table.hpp"
#include "show_script.hpp"
#include "support/test_support.hpp"

using namespace cupola;
using nlohmann::json;

namespace {

json base_config() { return json::parse(test::read_text(test::source_path("configs/dome-4ch.json"))); }

// Writes the config next to absolute paths of the repo's key, scene and show; returns its path.
std::string write_config(const std::string& test_name, json cfg) {
    const std::string dir = test::scratch_dir("config/" + test_name);
    for (const char* k : {"key_file", "scene", "show"})
        if (cfg.contains(k) && cfg[k].is_string()) cfg[k] = test::source_path("configs/" + cfg[k].get<std::string>());
    const std::string path = dir + "/cluster.json";
    test::write_text(path, cfg.dump(2));
    return path;
}

// Loads and expects a ConfigError whose message names the file and `field` and contains `words`.
void expect_error(const std::string& name, const json& cfg, const std::string& field, const std::string& words) {
    const std::string path = write_config(name, cfg);
    try {
        load_cluster_config(path);
        FAIL() << "no error for " << name;
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}

}  // namespace

// Every cluster config under configs/, with its scene and show, and every device table.
TEST(Config, ShippedConfigsLoad) {
    size_t loaded = 0;
    for (const auto& e : std::filesystem::directory_iterator(test::source_path("configs"))) {
        if (!e.is_regular_file() || e.path().extension() != ".json") continue;
        const std::string f = e.path().string();
        ClusterConfig c = load_cluster_config(f);
        EXPECT_FALSE(c.channels.empty()) << f;
        SceneConfig s = load_scene_config(c.scene_file);
        // The Sun, the Earth and the Moon, or the whole solar system with Jupiter's four large moons and Titan
        // (configs/scenes/solar-system.json).
        EXPECT_TRUE(s.bodies.size() == 3u || s.bodies.size() == 16u) << f;
        EXPECT_NE(s.find("earth"), nullptr) << f;
        const ShowScript show = ShowScript::load(c.show_file, s);
        EXPECT_FALSE(show.keyframes().empty()) << f;
        ++loaded;
    }
    EXPECT_GE(loaded, 5u);
    for (const auto& e : std::filesystem::directory_iterator(test::source_path("configs/input")))
        EXPECT_FALSE(load_device_table(e.path().string()).empty()) << e.path();
    ClusterConfig dome = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    EXPECT_EQ(dome.channels.size(), 4u);
    EXPECT_EQ(dome.network.transport, Transport::Multicast);
    EXPECT_FALSE(find_coverage_hole(dome.dome, dome.channels).has_value());
    EXPECT_EQ(load_cluster_config(test::source_path("configs/wall-3ch.json")).channels.size(), 3u);
    ClusterConfig eclipse = load_cluster_config(test::source_path("configs/eclipse-2006-dome.json"));
    EXPECT_EQ(eclipse.channels.size(), 4u);
    EXPECT_EQ(eclipse.network.transport, Transport::Unicast);
    ClusterConfig planets = load_cluster_config(test::source_path("configs/planets-tonight-dome.json"));
    EXPECT_EQ(planets.channels.size(), 4u);
    EXPECT_FALSE(find_coverage_hole(planets.dome, planets.channels).has_value());
    EXPECT_TRUE(eclipse.output.auto_exposure.enabled);
}

TEST(Config, UnknownKeyIsNamed) {
    json c = base_config();
    c["channels"][1]["fov"]["lef_deg"] = 40;
    expect_error("unknown_nested", c, "channels[1].fov.lef_deg", "unknown key");
    json t = base_config();
    t["netwrok"] = json::object();
    expect_error("unknown_top", t, "netwrok", "unknown key");
}

TEST(Config, MissingFieldIsNamed) {
    json c = base_config();
    c["channels"][2]["fov"].erase("up_deg");
    expect_error("missing_fov", c, "channels[2].fov.up_deg", "missing required field");
    json k = base_config();
    k.erase("key_file");
    expect_error("missing_key", k, "key_file", "missing required field");
    json ch = base_config();
    ch.erase("channels");
    expect_error("missing_channels", ch, "channels", "missing required field");
}

TEST(Config, MalformedValuesAreNamed) {
    json c = base_config();
    c["channels"][0]["fov"]["left_deg"] = "fifty";
    expect_error("string_for_number", c, "channels[0].fov.left_deg", "expected a number");
    json r = base_config();
    r["channels"][3]["fov"]["right_deg"] = 95;
    expect_error("out_of_range", r, "channels[3].fov.right_deg", "outside the allowed range");
    json t = base_config();
    t["network"]["transport"] = "carrier-pigeon";
    expect_error("bad_transport", t, "network.transport", "is not one of");
    json g = base_config();
    g["network"]["multicast_group"] = "10.1.2.3";
    expect_error("not_multicast", g, "network.multicast_group", "not a multicast address");
    json p = base_config();
    p["network"]["report_port"] = 70000;
    expect_error("bad_port", p, "network.report_port", "outside the allowed range");
    json d = base_config();
    d["channels"][1]["id"] = 0;
    expect_error("duplicate_id", d, "channels[1].id", "used twice");
    json f = base_config();
    f["output"]["formats"] = json::array({"png", "tiff"});
    expect_error("bad_format", f, "output.formats[1]", "not one of");
    json u = base_config();
    u["network"]["transport"] = "unicast";
    expect_error("unicast_needs_address", u, "channels[0].unicast_address", "missing required field");
    json m = base_config();
    m["key_file"] = "keys/does-not-exist.key";
    expect_error("missing_file", m, "key_file", "does not exist");
}

TEST(Config, InputSectionIsReadAndItsErrorsNamed) {
    json c = base_config();
    c["input"] = {{"usb", false}, {"dead_zone", 0.2}, {"goto_seconds", 2}, {"buttons", {{"3", "play"}, {"0", "none"}}}};
    const ClusterConfig cfg = load_cluster_config(write_config("input_ok", c));
    EXPECT_FALSE(cfg.input.usb);
    EXPECT_DOUBLE_EQ(cfg.input.dead_zone, 0.2);
    EXPECT_DOUBLE_EQ(cfg.input.goto_seconds, 2.0);
    EXPECT_EQ(cfg.input.button_actions.size(), 2u);
    EXPECT_EQ(cfg.input.button_actions.at(3), "play");
    json a = base_config();
    a["input"] = {{"buttons", {{"0", "launch"}}}};
    expect_error("input_bad_action", a, "input.buttons.0", "is not one of");
    json b = base_config();
    b["input"] = {{"buttons", {{"first", "play"}}}};
    expect_error("input_bad_button", b, "input.buttons.first", "0..31");
    json z = base_config();
    z["input"] = {{"dead_zone", 1.5}};
    expect_error("input_dead_zone", z, "input.dead_zone", "outside the allowed range");
    json t = base_config();
    t["input"] = {{"device_table", "input/none.json"}};
    expect_error("input_table", t, "input.device_table", "does not exist");
}

TEST(Config, SyntaxErrorNamesFileAndPosition) {
    const std::string dir = test::scratch_dir("config/syntax");
    test::write_text(dir + "/broken.json", "{\n  \"cluster_id\": 3,\n  \"channels\": [ }\n");
    try {
        load_cluster_config(dir + "/broken.json");
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
    }
    // A number beyond a double is a ConfigError too, not a stray nlohmann exception.
    test::write_text(dir + "/huge.json", "{\"cluster_id\": 1e777}");
    try {
        load_cluster_config(dir + "/huge.json");
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("huge.json"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("overflow"), std::string::npos) << e.what();
    }
}

TEST(Config, HoleInTheDomeIsAnError) {
    json c = base_config();
    c["channels"].erase(3);  // no channel looks left any more
    expect_error("hole", c, "channels", "hole in the dome");
    // The message says where the hole is: the left side of the dome (azimuth about -90).
    ClusterConfig ok = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    ok.channels.pop_back();
    auto hole = find_coverage_hole(ok.dome, ok.channels);
    ASSERT_TRUE(hole.has_value());
    EXPECT_LT(hole->azimuth_deg, -30.0);
    EXPECT_GT(hole->azimuth_deg, -150.0);
    // Narrowing every channel leaves a hole near the zenith or between channels.
    json n = base_config();
    for (auto& ch : n["channels"]) ch["fov"]["up_deg"] = 40;
    expect_error("narrow", n, "channels", "hole in the dome");
    // Allowed when coverage is not required (a wall, a partial dome).
    json a = base_config();
    a["channels"].erase(3);
    a["dome"]["require_full_coverage"] = false;
    EXPECT_NO_THROW(load_cluster_config(write_config("hole_allowed", a)));
}

TEST(Config, SceneErrorsAreNamed) {
    const std::string dir = test::scratch_dir("config/scene");
    json s = json::parse(test::read_text(test::source_path("configs/scenes/earth-moon.json")));
    s["stars"]["catalog"] = test::source_path("data/stars/bright_stars.csv");
    s["bodies"][1]["texture"] = "generated:earth";
    s["bodies"][2]["radius_m"] = -5;
    test::write_text(dir + "/scene.json", s.dump());
    try {
        load_scene_config(dir + "/scene.json");
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "bodies[2].radius_m");
    }
    s["bodies"][2]["radius_m"] = 1.7e6;
    s["bodies"][0]["kind"] = "galaxy";
    test::write_text(dir + "/scene.json", s.dump());
    try {
        load_scene_config(dir + "/scene.json");
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "bodies[0].kind");
    }
}

TEST(Config, AtmosphereAndExposureErrorsAreNamed) {
    const std::string dir = test::scratch_dir("config/atmosphere");
    json s = json::parse(test::read_text(test::source_path("configs/scenes/earth-physical.json")));
    s["stars"]["catalog"] = test::source_path("data/stars/bright_stars.csv");
    s["overlays"]["figures"] = test::source_path("data/sky/constellations.json");
    s["bodies"][1]["texture"] = "generated:earth";
    auto scene_error = [&](const json& scene, const std::string& field, const std::string& words) {
        test::write_text(dir + "/scene.json", scene.dump());
        try {
            load_scene_config(dir + "/scene.json");
            FAIL() << field;
        } catch (const ConfigError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    json bad = s;
    bad["bodies"][1]["atmosphere"]["model"] = "fastest";
    scene_error(bad, "bodies[1].atmosphere.model", "medium");  // the valid names are listed
    bad = s;
    bad["bodies"][1]["atmosphere"]["preset"] = "venus";
    scene_error(bad, "bodies[1].atmosphere.preset", "earth");
    // The night sky's brightness and the overlays.
    bad = s;
    bad["stars"]["bortle"] = 3;
    bad["stars"]["sky_brightness"] = 20.0;
    scene_error(bad, "stars.bortle", "not both");
    bad = s;
    bad["stars"]["bortle"] = 10;
    scene_error(bad, "stars.bortle", "");
    bad = s;
    bad["overlays"]["figures"] = dir + "/no-such-figures.json";
    scene_error(bad, "overlays.figures", "does not exist");
    bad = s;
    bad["overlays"]["grid_altaz"] = {{"width_deg", 50}};
    scene_error(bad, "overlays.grid_altaz.width_deg", "");
    bad = s;
    bad["overlays"]["grid_galactic"] = json::object();
    scene_error(bad, "overlays.grid_galactic", "");
    bad = s;
    bad["bodies"][1]["atmosphere"]["mie_g"] = 1.5;
    scene_error(bad, "bodies[1].atmosphere.mie_g", "");
    bad = s;
    bad["bodies"][1]["atmosphere"]["colour"] = "blue";
    scene_error(bad, "bodies[1].atmosphere.colour", "");
    bad = s;
    bad["bodies"][0]["atmosphere"] = {{"preset", "earth"}};
    scene_error(bad, "bodies[0].atmosphere.preset", "star");
    bad = s;
    bad["bodies"][1]["atmosphere"]["top_altitude_m"] = 5000;  // thinner than the 8 km scale height
    scene_error(bad, "bodies[1].atmosphere.top_altitude_m", "scale height");
    // A good one resolves the preset onto the body's radius.
    test::write_text(dir + "/scene.json", s.dump());
    const SceneConfig ok = load_scene_config(dir + "/scene.json");
    EXPECT_TRUE(ok.bodies[1].atmosphere.present);
    EXPECT_DOUBLE_EQ(ok.bodies[1].atmosphere.parameters.bottom_radius, ok.bodies[1].radius_m);
    EXPECT_DOUBLE_EQ(ok.bodies[1].atmosphere.parameters.top_radius, ok.bodies[1].radius_m + 60000.0);
    EXPECT_FALSE(ok.bodies[2].atmosphere.present);

    json c = json::parse(test::read_text(test::source_path("configs/descent-1ch.json")));
    c["output"]["auto_exposure"]["min_exposure"] = 10.0;
    c["output"]["auto_exposure"]["max_exposure"] = 1.0;
    expect_error("auto_exposure_range", c, "output.auto_exposure.min_exposure", "max_exposure");
}

// A missing texture or star catalogue is a start-up error naming the file, the field and the
// path, in the loader and in a real slave process (which must not render black frames instead).
TEST(Config, MissingTextureOrCatalogueStopsTheStartWithAClearError) {
    const std::string dir = test::scratch_dir("config/missing_files");
    json s = json::parse(test::read_text(test::source_path("configs/scenes/earth-moon.json")));
    s["stars"]["catalog"] = test::source_path("data/stars/bright_stars.csv");
    s["overlays"]["figures"] = test::source_path("data/sky/constellations.json");
    s["bodies"][1]["texture"] = dir + "/no-such-earth.png";
    test::write_text(dir + "/scene.json", s.dump());
    try {
        load_scene_config(dir + "/scene.json");
        FAIL() << "a missing texture was accepted";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "bodies[1].texture");
        EXPECT_NE(std::string(e.what()).find("no-such-earth.png"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(dir + "/scene.json"), std::string::npos) << e.what();
    }
    s["bodies"][1]["texture"] = "generated:earth";
    s["stars"]["catalog"] = dir + "/no-such-stars.csv";
    test::write_text(dir + "/scene.json", s.dump());
    try {
        load_scene_config(dir + "/scene.json");
        FAIL() << "a missing catalogue was accepted";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "stars.catalog");
        EXPECT_NE(std::string(e.what()).find("no-such-stars.csv"), std::string::npos) << e.what();
    }
    // The slave refuses to start, and says why.
    json c = json::parse(test::read_text(test::source_path("configs/dome-4ch.json")));
    c["key_file"] = test::source_path("configs/keys/loopback.key");
    c["show"] = test::source_path("configs/shows/earth-moon.json");
    c["scene"] = dir + "/scene.json";
    test::write_text(dir + "/cluster.json", c.dump());
    const auto [status, out] = test::run_shell(test::bin_path("cupola-slave") + " --config " + dir +
                                               "/cluster.json --channel 0 --out " + dir + "/out 2>&1");
    EXPECT_EQ(status, 2) << out;
    EXPECT_NE(out.find("stars.catalog"), std::string::npos) << out;
    EXPECT_NE(out.find("no-such-stars.csv"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out/"
                                               "frame_000000.png"));
}
