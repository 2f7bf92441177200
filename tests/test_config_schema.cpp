// The JSON Schemas in configs/schema/ are the one declaration of every config field. Checked here:
// every shipped config validates (valijson, a real draft-07 validator) and loads with the reader;
// broken configs are rejected by both, naming the same field; the readers' defaults are the
// structs' defaults; the names the code knows are the schemas' enums.
#include <gtest/gtest.h>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "atmosphere/production_quality.hpp"
#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "config/config_schema.hpp"
#include "config/scene_config.hpp"
#include "easing.hpp"
#include "input/device_table.hpp"
#include "show_script.hpp"
#include "support/test_support.hpp"

using namespace cupola;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

json read_json(const std::string& path) { return json::parse(test::read_text(path)); }

// A schema file of configs/schema/, parsed by valijson.
const valijson::Schema& schema(const std::string& name) {
    static std::map<std::string, std::unique_ptr<valijson::Schema>> cache;
    auto& s = cache[name];
    if (!s) {
        static std::map<std::string, json> docs;
        docs[name] = read_json(test::source_path("configs/schema/" + name + ".schema.json"));
        s = std::make_unique<valijson::Schema>();
        valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
        valijson::adapters::NlohmannJsonAdapter adapter(docs[name]);
        parser.populateSchema(adapter, *s);
    }
    return *s;
}

// The reader's field path ("channels[1].fov.left_deg") of a valijson error: its context walks
// the document ("<root>", "[channels]", "[1]", "[fov]"); required, unknown and failing
// properties are named in the description.
std::string field_of(const valijson::ValidationResults::Error& e, const json& doc) {
    std::string path;
    const json* node = &doc;
    for (size_t i = 1; i < e.context.size(); ++i) {
        const std::string key = e.context[i].substr(1, e.context[i].size() - 2);
        if (node->is_array()) {
            path += "[" + key + "]";
            node = &node->at(std::stoul(key));
        } else {
            path += (path.empty() ? "" : ".") + key;
            node = node->contains(key) ? &node->at(key) : node;
        }
    }
    for (const std::string marker :
         {"Missing required property '", "additionalProperties' constraints: '", "associated with property name '"}) {
        const auto at = e.description.find(marker);
        if (at == std::string::npos) continue;
        const auto from = at + marker.size();
        path += (path.empty() ? "" : ".") + e.description.substr(from, e.description.find('\'', from) - from);
    }
    return path;
}

size_t depth(const std::string& path) {
    return std::count(path.begin(), path.end(), '.') + std::count(path.begin(), path.end(), '[');
}

// The most specific fields the schema finds wrong (valijson also reports every enclosing one);
// empty when the document is valid.
std::set<std::string> schema_errors(const std::string& name, const json& doc, std::string* all = nullptr) {
    valijson::Validator validator;
    valijson::ValidationResults results;
    valijson::adapters::NlohmannJsonAdapter adapter(doc);
    if (validator.validate(schema(name), adapter, &results)) return {};
    std::vector<std::string> fields;
    for (const auto& e : results) {
        fields.push_back(field_of(e, doc));
        if (all) *all += fields.back() + ": " + e.description + "\n";
    }
    size_t deepest = 0;
    for (const auto& f : fields) deepest = std::max(deepest, depth(f));
    std::set<std::string> out;
    for (const auto& f : fields)
        if (depth(f) == deepest) out.insert(f);
    return out;
}

std::vector<std::string> files_in(const std::string& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(test::source_path(dir)))
        if (e.is_regular_file() && e.path().extension() == ".json") out.push_back(e.path().string());
    std::sort(out.begin(), out.end());
    return out;
}

// The documents below are written to scratch files with the paths they name made absolute, so the
// reader finds the repository's key, scene, show, catalogue.
std::string write_cluster(const std::string& name, json cfg) {
    for (const char* k : {"key_file", "scene", "show"})
        if (cfg.contains(k) && cfg[k].is_string()) cfg[k] = test::source_path("configs/" + cfg[k].get<std::string>());
    const std::string path = test::scratch_dir("config_schema/" + name) + "/cluster.json";
    test::write_text(path, cfg.dump(2));
    return path;
}

json shipped_scene() {
    json s = read_json(test::source_path("configs/scenes/earth-moon.json"));
    s["stars"]["catalog"] = test::source_path("data/stars/bright_stars.csv");
    s["overlays"]["figures"] = test::source_path("data/sky/constellations.json");
    s["bodies"][1]["texture"] = "generated:earth";
    return s;
}

std::string write_doc(const std::string& name, const json& doc) {
    const std::string path = test::scratch_dir("config_schema/" + name) + "/doc.json";
    test::write_text(path, doc.dump(2));
    return path;
}

// Runs a reader on the written document; returns the field of its ConfigError, or "" when it
// accepted the document.
using Reader = std::function<void(const std::string& path)>;
std::string reader_error(const Reader& read, const std::string& path) {
    try {
        read(path);
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        return e.field();
    }
    return "";
}

const Reader read_cluster = [](const std::string& p) { load_cluster_config(p); };
const Reader read_scene = [](const std::string& p) { load_scene_config(p); };
const Reader read_show = [](const std::string& p) {
    static const SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    ShowScript::load(p, scene);
};
const Reader read_devices = [](const std::string& p) { load_device_table(p); };

struct Broken {
    const char* what;
    std::function<void(json&)> spoil;
    const char* field;                   // the field both must name
    const char* schema_field = nullptr;  // where valijson names it, when it cannot name the field
};

// Both reject every broken document, naming the same field.
void expect_agreement(const std::string& schema_name, const json& good, const Reader& read,
                      const std::vector<Broken>& cases) {
    ASSERT_TRUE(schema_errors(schema_name, good).empty());
    for (const auto& c : cases) {
        json doc = good;
        c.spoil(doc);
        const std::string path = schema_name == "cluster" ? write_cluster(c.what, doc) : write_doc(c.what, doc);
        std::string report;
        const std::set<std::string> found = schema_errors(schema_name, doc, &report);
        EXPECT_TRUE(found.count(c.schema_field ? c.schema_field : c.field)) << c.what << ": the schema names\n"
                                                                            << report;
        EXPECT_EQ(reader_error(read, path), c.field) << c.what;
    }
}

}  // namespace

TEST(ConfigSchema, EveryShippedConfigValidates) {
    const std::vector<std::pair<std::string, std::string>> kinds = {
        {"configs", "cluster"}, {"configs/scenes", "scene"}, {"configs/shows", "show"}, {"configs/input", "devices"}};
    size_t checked = 0;
    for (const auto& [dir, name] : kinds) {
        for (const auto& file : files_in(dir)) {
            std::string report;
            EXPECT_TRUE(schema_errors(name, read_json(file), &report).empty()) << file << "\n" << report;
            ++checked;
        }
    }
    EXPECT_GE(checked, 11u);
}

TEST(ConfigSchema, CompiledInSchemasAreTheFiles) {
    for (const auto& name : config_schema_names())
        EXPECT_EQ(config_schema(name), read_json(test::source_path("configs/schema/" + name + ".schema.json"))) << name;
}

TEST(ConfigSchema, ClusterReaderAndSchemaAgreeOnBrokenConfigs) {
    const json good = read_json(test::source_path("configs/dome-4ch.json"));
    const auto set = [](const char* ptr, json v) {
        return [p = std::string(ptr), v](json& d) { d[json::json_pointer(p)] = v; };
    };
    const auto erase = [](const char* ptr, const char* key) {
        return [p = std::string(ptr), k = std::string(key)](json& d) { d[json::json_pointer(p)].erase(k); };
    };
    expect_agreement(
        "cluster", good, read_cluster,
        {
            {"wrong_type", set("/channels/0/fov/left_deg", "fifty"), "channels[0].fov.left_deg"},
            {"out_of_range", set("/channels/3/fov/right_deg", 95), "channels[3].fov.right_deg"},
            {"unknown_enum", set("/network/transport", "carrier-pigeon"), "network.transport"},
            {"missing_field", erase("/channels/2/fov", "up_deg"), "channels[2].fov.up_deg"},
            {"missing_top", erase("", "key_file"), "key_file"},
            {"negative_size", set("/output/width", -5), "output.width"},
            {"negative_channel_size", set("/channels/1/height", -1), "channels[1].height"},
            {"channel_id_too_big", set("/channels/0/id", 5000), "channels[0].id"},
            {"channel_id_not_integer", set("/channels/2/id", 1.5), "channels[2].id"},
            {"unknown_key", set("/channels/1/fov/lef_deg", 40), "channels[1].fov.lef_deg"},
            {"unknown_top_key", set("/netwrok", json::object()), "netwrok"},
            {"port_too_big", set("/network/report_port", 70000), "network.report_port"},
            {"bad_format", set("/output/formats", json::array({"png", "tiff"})), "output.formats[1]"},
            {"no_address", set("/network/transport", "unicast"), "channels[0].unicast_address"},
            {"bad_address", set("/channels/1/unicast_address", "127.0.0.1:99999"), "channels[1].unicast_address"},
            {"bad_ipv4", set("/network/master_address", "127.0.1"), "network.master_address"},
            {"bad_name", set("/channels/0/name", "front door"), "channels[0].name"},
            // valijson reports a key that fails propertyNames at the object that holds it.
            {"bad_button", set("/input", {{"buttons", {{"first", "play"}}}}), "input.buttons.first", "input.buttons"},
            {"bad_action", set("/input", {{"buttons", {{"0", "launch"}}}}), "input.buttons.0"},
            {"dead_zone", set("/input", {{"dead_zone", 1.5}}), "input.dead_zone"},
            {"cluster_id", set("/cluster_id", -1), "cluster_id"},
            {"bool_type", set("/dome/require_full_coverage", "yes"), "dome.require_full_coverage"},
            {"auto_exposure_key", set("/output/auto_exposure", {{"key", 0}}), "output.auto_exposure.key"},
            {"no_channels", set("/channels", json::array()), "channels"},
        });
}

TEST(ConfigSchema, SceneShowAndDeviceReadersAndSchemasAgree) {
    const auto set = [](const char* ptr, json v) {
        return [p = std::string(ptr), v](json& d) { d[json::json_pointer(p)] = v; };
    };
    const auto erase = [](const char* ptr, const char* key) {
        return [p = std::string(ptr), k = std::string(key)](json& d) { d[json::json_pointer(p)].erase(k); };
    };
    expect_agreement(
        "scene", shipped_scene(), read_scene,
        {
            {"negative_radius", set("/bodies/2/radius_m", -5), "bodies[2].radius_m"},
            {"unknown_kind", set("/bodies/0/kind", "galaxy"), "bodies[0].kind"},
            {"odd_streaks", set("/glare/streak_count", 95), "glare.streak_count"},
            {"mie_g", set("/bodies/1/atmosphere/mie_g", 1.5), "bodies[1].atmosphere.mie_g"},
            {"model", set("/bodies/1/atmosphere/model", "fastest"), "bodies[1].atmosphere.model"},
            {"no_catalog", erase("/stars", "catalog"), "stars.catalog"},
            {"unknown_key", set("/bodies/1/atmosphere/colour", "blue"), "bodies[1].atmosphere.colour"},
            {"umbra_light", set("/bodies/2/umbra_light", json::array({0.1, 0.2})), "bodies[2].umbra_light"},
            {"mode", set("/shadows/mode", "soft"), "shadows.mode"},
            {"no_children", set("/shadows/groups/0/children", json::array()), "shadows.groups[0].children"},
        });
    const json show = read_json(test::source_path("configs/shows/earth-moon.json"));
    expect_agreement(
        "show", show, read_show,
        {
            {"easing", set("/keyframes/0/easing", "bouncy"), "keyframes[0].easing"},
            {"no_time", erase("/keyframes/1", "time_utc"), "keyframes[1].time_utc"},
            {"negative_time", set("/keyframes/0/at_s", -1), "keyframes[0].at_s"},
            {"elevation", set("/keyframes/1/camera/target_elevation_deg", 91),
             "keyframes[1].camera.target_elevation_deg"},
            {"exposure", set("/events", json::array({{{"at_s", 1}, {"exposure", "manual"}}})), "events[0].exposure"},
            {"interval", set("/frame_interval_s", 0), "frame_interval_s"},
        });
    const json devices = read_json(test::source_path("configs/input/devices.json"));
    expect_agreement(
        "devices", devices, read_devices,
        {
            {"vendor", set("/devices/0/vendor_id", "46d"), "devices[0].vendor_id"},
            {"bits", set("/devices/0/reports/0/fields/0/bits", 40), "devices[0].reports[0].fields[0].bits"},
            {"kind", set("/devices/1/kind", "joystick"), "devices[1].kind"},
            {"axis", set("/devices/1/reports/0/fields/2/axis", "sideways"), "devices[1].reports[0].fields[2].axis"},
            {"no_report_id", erase("/devices/0/reports/1", "id"), "devices[0].reports[1].id"},
        });
}

// What a schema cannot say: files that must exist, values that must differ or be unique, sums
// and orders across fields, names that must be bodies of the scene, the dome coverage. The
// schema accepts these documents; the reader rejects them, naming the field.
TEST(ConfigSchema, CrossFieldRulesAreTheReadersAlone) {
    const json good = read_json(test::source_path("configs/dome-4ch.json"));
    const std::vector<std::tuple<const char*, std::function<void(json&)>, const char*>> cases = {
        {"duplicate_id", [](json& d) { d["channels"][1]["id"] = 0; }, "channels[1].id"},
        {"duplicate_name", [](json& d) { d["channels"][2]["name"] = "front"; }, "channels[2].name"},
        {"missing_file", [](json& d) { d["key_file"] = "keys/does-not-exist.key"; }, "key_file"},
        {"not_multicast", [](json& d) { d["network"]["multicast_group"] = "10.1.2.3"; }, "network.multicast_group"},
        {"same_ports", [](json& d) { d["network"]["report_port"] = 47600; }, "network.report_port"},
        {"fov_sum", [](json& d) { d["channels"][0]["fov"]["right_deg"] = -52; }, "channels[0].fov.right_deg"},
        {"hole", [](json& d) { d["channels"].erase(3); }, "channels"},
        {"exposure_order",
         [](json& d) {
             d["output"]["auto_exposure"] = {{"min_exposure", 10.0}, {"max_exposure", 1.0}};
         },
         "output.auto_exposure.min_exposure"},
    };
    for (const auto& [what, spoil, field] : cases) {
        json doc = good;
        spoil(doc);
        EXPECT_TRUE(schema_errors("cluster", doc).empty()) << what;
        EXPECT_EQ(reader_error(read_cluster, write_cluster(std::string("reader_only_") + what, doc)), field) << what;
    }
    json scene = shipped_scene();
    scene["bodies"][2]["name"] = "earth";
    EXPECT_TRUE(schema_errors("scene", scene).empty());
    EXPECT_EQ(reader_error(read_scene, write_doc("reader_only_scene", scene)), "bodies[2].name");
    json show = read_json(test::source_path("configs/shows/earth-moon.json"));
    show["keyframes"][1]["at_s"] = 0;
    EXPECT_TRUE(schema_errors("show", show).empty());
    EXPECT_EQ(reader_error(read_show, write_doc("reader_only_show", show)), "keyframes[1].at_s");
    show = read_json(test::source_path("configs/shows/earth-moon.json"));
    show["keyframes"][0]["camera"]["look_at"] = "pluto";
    EXPECT_TRUE(schema_errors("show", show).empty());
    EXPECT_EQ(reader_error(read_show, write_doc("reader_only_body", show)), "keyframes[0].camera.look_at");
}

// Every optional section left empty: the reader fills in the declared defaults, which must be
// the structs' own (the structs are what code that builds a config without a file gets).
TEST(ConfigSchema, DeclaredDefaultsAreTheStructDefaults) {
    json c = read_json(test::source_path("configs/dome-4ch.json"));
    for (const char* k : {"frame_rate_hz", "network", "dome", "output"}) c.erase(k);
    for (auto& ch : c["channels"]) ch.erase("name");
    const ClusterConfig got = load_cluster_config(write_cluster("defaults", c));
    const ClusterConfig want{};
    EXPECT_EQ(got.frame_rate_hz, want.frame_rate_hz);
    EXPECT_EQ(got.egl_device, want.egl_device);
    const NetworkConfig &n = got.network, &wn = want.network;
    EXPECT_EQ(n.transport, wn.transport);
    EXPECT_EQ(n.multicast_group, wn.multicast_group);
    EXPECT_EQ(n.interface_address, wn.interface_address);
    EXPECT_EQ(n.broadcast_address, wn.broadcast_address);
    EXPECT_EQ(n.master_address, wn.master_address);
    EXPECT_EQ(n.snapshot_port, wn.snapshot_port);
    EXPECT_EQ(n.report_port, wn.report_port);
    EXPECT_EQ(n.max_datagram_bytes, wn.max_datagram_bytes);
    EXPECT_EQ(n.channel_timeout_ms, wn.channel_timeout_ms);
    EXPECT_EQ(n.resend_interval_ms, wn.resend_interval_ms);
    EXPECT_EQ(n.hello_wait_ms, wn.hello_wait_ms);
    EXPECT_EQ(n.strict_key_permissions, wn.strict_key_permissions);
    EXPECT_EQ(got.dome.fov_deg, want.dome.fov_deg);
    EXPECT_EQ(got.dome.tilt_deg, want.dome.tilt_deg);
    EXPECT_EQ(got.dome.require_full_coverage, want.dome.require_full_coverage);
    EXPECT_EQ(got.output.formats, want.output.formats);
    EXPECT_EQ(got.output.domemaster_size, want.output.domemaster_size);
    EXPECT_EQ(got.output.exposure, want.output.exposure);
    EXPECT_EQ(got.output.auto_exposure.enabled, want.output.auto_exposure.enabled);
    const InputConfig &in = got.input, &wi = want.input;
    EXPECT_EQ(in.usb, wi.usb);
    EXPECT_EQ(in.dead_zone, wi.dead_zone);
    EXPECT_EQ(in.smoothing_s, wi.smoothing_s);
    EXPECT_EQ(in.speed_per_altitude, wi.speed_per_altitude);
    EXPECT_EQ(in.min_speed_m_s, wi.min_speed_m_s);
    EXPECT_EQ(in.turn_rate_deg_s, wi.turn_rate_deg_s);
    EXPECT_EQ(in.orbit_rate_deg_s, wi.orbit_rate_deg_s);
    EXPECT_EQ(in.goto_seconds, wi.goto_seconds);
    EXPECT_EQ(in.takeover, wi.takeover);
    EXPECT_EQ(in.button_actions, wi.button_actions);
    const ChannelConfig wc{};
    EXPECT_EQ(got.channels[0].width, wc.width);
    EXPECT_EQ(got.channels[0].height, wc.height);
    EXPECT_EQ(got.channels[0].orientation.roll_deg, wc.orientation.roll_deg);
    EXPECT_EQ(got.channels[0].name, "channel0");

    // A present auto_exposure or glare section is on unless it says otherwise (the structs'
    // enabled = false stands for the absent section); its other fields are the structs'.
    c["output"] = {{"auto_exposure", json::object()}};
    const AutoExposureConfig ae = load_cluster_config(write_cluster("defaults_ae", c)).output.auto_exposure;
    const AutoExposureConfig wae{};
    EXPECT_TRUE(ae.enabled);
    EXPECT_EQ(ae.key, wae.key);
    EXPECT_EQ(ae.min_exposure, wae.min_exposure);
    EXPECT_EQ(ae.max_exposure, wae.max_exposure);

    json s = shipped_scene();
    s["glare"] = json::object();
    s["shadows"] = {{"groups", s["shadows"]["groups"]}};
    s["stars"] = {{"catalog", s["stars"]["catalog"]}};
    s["bodies"][1]["atmosphere"].erase("model");
    s["bodies"][2] = {{"name", "moon"}, {"kind", "moon"}, {"ephemeris", "moon"}, {"radius_m", 1.7374e6}};
    const SceneConfig scene = load_scene_config(write_doc("defaults_scene", s));
    const GlareConfig& g = scene.glare;
    const GlareConfig wg{};
    EXPECT_TRUE(g.enabled);
    EXPECT_EQ(g.strength, wg.strength);
    EXPECT_EQ(g.extent_deg, wg.extent_deg);
    EXPECT_EQ(g.halo_radius_deg, wg.halo_radius_deg);
    EXPECT_EQ(g.halo_width_deg, wg.halo_width_deg);
    EXPECT_EQ(g.halo_fraction, wg.halo_fraction);
    EXPECT_EQ(g.streak_count, wg.streak_count);
    EXPECT_EQ(g.streak_contrast, wg.streak_contrast);
    EXPECT_EQ(g.animation_rate, wg.animation_rate);
    EXPECT_EQ(g.visibility, wg.visibility);
    EXPECT_EQ(g.min_display, wg.min_display);
    EXPECT_EQ(g.max_sources, wg.max_sources);
    EXPECT_EQ(g.probe_size, wg.probe_size);
    const StarFieldConfig ws{};
    EXPECT_EQ(scene.stars.magnitude_limit, ws.magnitude_limit);
    EXPECT_EQ(scene.stars.psf_sigma_arcmin, ws.psf_sigma_arcmin);
    EXPECT_EQ(scene.stars.zero_mag_flux, ws.zero_mag_flux);
    const ShadowConfig wsh{};
    EXPECT_EQ(scene.shadows.mode, wsh.mode);
    EXPECT_EQ(scene.shadows.butterworth_order, wsh.butterworth_order);
    EXPECT_EQ(scene.shadows.groups[0].siblings_shadow_each_other, ShadowGroupConfig{}.siblings_shadow_each_other);
    const BodyConfig& b = scene.bodies[2];
    const BodyConfig wb{};
    EXPECT_EQ(b.albedo, wb.albedo);
    EXPECT_EQ(b.limb_darkening_u, wb.limb_darkening_u);
    EXPECT_EQ(b.radiance, wb.radiance);
    EXPECT_EQ(b.umbra_brightness, wb.umbra_brightness);
    EXPECT_EQ(b.corona, wb.corona);
    EXPECT_EQ(b.tint, wb.tint);
    EXPECT_EQ(b.texture, "generated:moon");
    EXPECT_EQ(scene.bodies[1].atmosphere.model, AtmosphereConfig{}.model);

    json sh = read_json(test::source_path("configs/shows/eclipse-2006-ground.json"));
    sh.erase("frame_interval_s");
    sh["keyframes"][0]["camera"]["observer"].erase("alt_m");
    sh["keyframes"][0]["camera"].erase("look_azimuth_deg");
    const ShowScript show = ShowScript::load(write_doc("defaults_show", sh), scene);
    const ShowKeyframe& k = show.keyframes()[0];
    const ShowKeyframe wk{};
    EXPECT_EQ(show.frame_interval_s(), 1.0 / 30.0);
    EXPECT_EQ(k.camera_easing, wk.camera_easing);
    EXPECT_EQ(k.time_easing, wk.time_easing);
    EXPECT_EQ(k.camera.target_elevation_deg, wk.camera.target_elevation_deg);
    const ObserverSite wo{};
    EXPECT_EQ(k.camera.observer->alt_m, wo.alt_m);
    EXPECT_EQ(k.camera.observer->look_azimuth_deg, wo.look_azimuth_deg);
    EXPECT_EQ(k.camera.observer->look_elevation_deg, wo.look_elevation_deg);

    json d = read_json(test::source_path("configs/input/devices.json"));
    d["devices"][1].erase("interface");
    const DeviceModel m = load_device_table(write_doc("defaults_devices", d))[1];
    EXPECT_EQ(m.interface_number, DeviceModel{}.interface_number);
}

// The names the code maps to its enums are the schemas' allowed values, in the same order (the
// error messages list them).
TEST(ConfigSchema, CodeNamesAreTheDeclaredEnums) {
    const auto enum_of = [](const std::string& schema_name, const std::string& pointer) {
        const json& s = config_schema(schema_name);
        const json& node = s.at(json::json_pointer(pointer));
        return node.at("enum").get<std::vector<std::string>>();
    };
    EXPECT_EQ(enum_of("cluster", "/properties/input/properties/buttons/additionalProperties"), button_action_names());
    EXPECT_EQ(enum_of("scene", "/properties/shadows/properties/mode"), shadow_mode_names());
    EXPECT_EQ(enum_of("show", "/definitions/shadow_mode"), shadow_mode_names());
    EXPECT_EQ(enum_of("show", "/definitions/easing"), easing_names());
    EXPECT_EQ(enum_of("scene", "/properties/bodies/items/properties/atmosphere/properties/model"),
              atmosphere::production_quality_names());
    std::set<NavAxis> axes;
    for (const auto& name : enum_of(
             "devices", "/properties/devices/items/properties/reports/items/properties/fields/items/properties/axis")) {
        ASSERT_TRUE(nav_axis_from_name(name).has_value()) << name;
        axes.insert(*nav_axis_from_name(name));
        EXPECT_EQ(nav_axis_name(*nav_axis_from_name(name)), name);
    }
    EXPECT_EQ(axes.size(), 6u);
}
