#include "config/cluster_config.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "calibration/calibration_error.hpp"
#include "calibration/bourke_mesh.hpp"
#include "calibration/mpcdi_package.hpp"
#include "config/config_schema.hpp"
#include "config/json_reader.hpp"
#include "projection/fisheye.hpp"

namespace cupola {

namespace fs = std::filesystem;

std::string resolve_path(const std::string& base_dir, const std::string& path) {
    if (path.empty()) return path;
    fs::path p(path);
    if (p.is_absolute()) return p.lexically_normal().string();
    return (fs::path(base_dir) / p).lexically_normal().string();
}

const ChannelConfig& ClusterConfig::channel(int id) const {
    for (const auto& c : channels)
        if (c.id == id) return c;
    throw std::out_of_range(file + ": no channel with id " + std::to_string(id));
}

namespace {

// Defaults and ranges of every field: configs/schema/cluster.schema.json (JsonReader::declared_*).
// What a schema cannot say is checked here: files that must exist, a multicast group with the
// multicast transport, distinct ports, unique channel ids and names, min <= max exposure, the
// sum of opposite fov angles, and the dome coverage.

std::string ipv4(const JsonReader& r, const std::string& key) {
    std::string s = r.declared_string(key);
    in_addr a{};
    if (inet_pton(AF_INET, s.c_str(), &a) != 1) r.fail(key, "\"" + s + "\" is not an IPv4 address");
    return s;
}

bool all_digits(const std::string& s) {
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

void check_host_port(const JsonReader& r, const std::string& key, const std::string& s) {
    auto colon = s.rfind(':');
    in_addr a{};
    if (colon == std::string::npos || inet_pton(AF_INET, s.substr(0, colon).c_str(), &a) != 1)
        r.fail(key, "\"" + s + "\" is not of the form IPv4:port");
    try {
        const std::string digits = s.substr(colon + 1);
        if (!all_digits(digits)) throw std::invalid_argument("port");
        const int port = std::stoi(digits);
        if (port < 1 || port > 65535) throw std::invalid_argument("port");
    } catch (const std::exception&) {
        r.fail(key, "\"" + s + "\" has no valid port (1..65535)");
    }
}

NetworkConfig read_network(const JsonReader& r) {
    NetworkConfig n;
    std::string t = r.declared_choice("transport");
    n.transport = t == "multicast"   ? Transport::Multicast
                  : t == "broadcast" ? Transport::Broadcast
                                     : Transport::Unicast;
    n.multicast_group = ipv4(r, "multicast_group");
    if (n.transport == Transport::Multicast) {
        in_addr a{};
        inet_pton(AF_INET, n.multicast_group.c_str(), &a);
        uint32_t h = ntohl(a.s_addr);
        if ((h >> 28) != 0xE)
            r.fail("multicast_group", "\"" + n.multicast_group + "\" is not a multicast address (224.0.0.0/4)");
    }
    n.interface_address = ipv4(r, "interface_address");
    n.broadcast_address = ipv4(r, "broadcast_address");
    n.master_address = ipv4(r, "master_address");
    n.snapshot_port = static_cast<uint16_t>(r.declared_integer("snapshot_port"));
    n.report_port = static_cast<uint16_t>(r.declared_integer("report_port"));
    if (n.report_port == n.snapshot_port) r.fail("report_port", "must differ from snapshot_port");
    n.max_datagram_bytes = static_cast<int>(r.declared_integer("max_datagram_bytes"));
    n.channel_timeout_ms = static_cast<int>(r.declared_integer("channel_timeout_ms"));
    n.first_frame_timeout_ms = static_cast<int>(r.declared_integer("first_frame_timeout_ms"));
    n.resend_interval_ms = static_cast<int>(r.declared_integer("resend_interval_ms"));
    n.hello_wait_ms = static_cast<int>(r.declared_integer("hello_wait_ms"));
    n.strict_key_permissions = r.declared_boolean("strict_key_permissions");
    n.swap_lock = r.declared_boolean("swap_lock");
    r.reject_unknown_keys();
    return n;
}

FovDeg read_fov(const JsonReader& f) {
    FovDeg fov;
    fov.left_deg = f.declared_number("left_deg");
    fov.right_deg = f.declared_number("right_deg");
    fov.up_deg = f.declared_number("up_deg");
    fov.down_deg = f.declared_number("down_deg");
    if (fov.left_deg + fov.right_deg <= 0.1) f.fail("right_deg", "left_deg + right_deg must be positive");
    if (fov.up_deg + fov.down_deg <= 0.1) f.fail("up_deg", "up_deg + down_deg must be positive");
    f.reject_unknown_keys();
    return fov;
}

// output.window / output.kms (or a channel's): the declared defaults for what is not given.
WindowOutputConfig read_window_output(const JsonReader& w) {
    WindowOutputConfig c;
    c.display = w.string("display", "");
    c.output_name = w.declared_string("output_name");
    c.fullscreen = w.declared_boolean("fullscreen");
    w.reject_unknown_keys();
    return c;
}

// "WIDTHxHEIGHT" or "WIDTHxHEIGHT@HZ"; empty: the preferred mode.
void read_kms_mode(const JsonReader& k, KmsOutputConfig& c) {
    const std::string mode = k.declared_string("mode");
    if (mode.empty()) return;
    int w = 0, h = 0, used = 0;
    double hz = 0.0;
    const bool sized = std::sscanf(mode.c_str(), "%dx%d%n", &w, &h, &used) == 2;
    const bool rated = sized && mode[used] == '@' && std::sscanf(mode.c_str() + used + 1, "%lf%n", &hz, &used) == 1;
    const size_t end = rated ? mode.find('@') + 1 + used : used;
    if (!sized || w <= 0 || h <= 0 || w > 16384 || h > 16384 || (mode[used] == '@' && !rated) || end != mode.size() ||
        (rated && !(hz > 0.0 && hz < 1000.0)))
        k.fail("mode", "\"" + mode + "\" is not WIDTHxHEIGHT or WIDTHxHEIGHT@HZ (e.g. \"1920x1080@60\")");
    c.mode_width = w;
    c.mode_height = h;
    c.mode_refresh_hz = hz;
}

KmsOutputConfig read_kms_output(const JsonReader& k) {
    KmsOutputConfig c;
    c.device = k.declared_string("device");
    c.connector = k.declared_string("connector");
    read_kms_mode(k, c);
    k.reject_unknown_keys();
    return c;
}

// "sink": one name or a list of them.
std::vector<std::string> read_sink_names(const JsonReader& r) {
    const std::vector<std::string> allowed = {"files", "window", "kms"};
    std::vector<std::string> names;
    if (r.raw().at("sink").is_string())
        names = {r.one_of("sink", allowed)};
    else
        names = r.strings("sink", {});
    if (names.empty()) r.fail("sink", "name at least one of \"files\", \"window\", \"kms\"");
    for (size_t i = 0; i < names.size(); ++i)
        if (std::find(allowed.begin(), allowed.end(), names[i]) == allowed.end())
            throw ConfigError(r.file(), r.field("sink") + "[" + std::to_string(i) + "]",
                              "\"" + names[i] + "\" is not a sink (files, window, kms)");
    return names;
}

// The sink keys of `r` (the output section, or a channel's) over `base`; then the checks that
// need the whole: a window sink needs a display, and window and kms exclude each other.
SinkConfig read_sinks(const JsonReader& r, const SinkConfig& base) {
    SinkConfig c = base;
    if (r.has("sink")) c.sinks = read_sink_names(r);
    if (auto w = r.optional_child("window")) c.window = read_window_output(*w);
    if (auto k = r.optional_child("kms")) c.kms = read_kms_output(*k);
    if (c.has("window") && c.has("kms"))
        r.fail("sink", "window and kms cannot run in one slave (one GL context, one platform)");
    if (c.has("window") && c.window.display.empty())
        throw ConfigError(r.file(), r.field("window") + ".display",
                          "required when a sink is window (an X11 display name such as \":0\")");
    return c;
}

// The channel's MPCDI region: the package is opened to find the region, its raster and frustum.
// A Paul Bourke mesh: the raster size is the config's (the file has none); no frustum.
ChannelCalibration read_bourke_calibration(const JsonReader& k, const std::string& directory) {
    ChannelCalibration cal;
    cal.bourke_file = resolve_path(directory, k.string("bourke"));
    if (!fs::is_regular_file(cal.bourke_file)) k.fail("bourke", "file \"" + cal.bourke_file + "\" does not exist");
    cal.raster_width = static_cast<int>(k.required_integer("raster_width"));
    cal.raster_height = static_cast<int>(k.required_integer("raster_height"));
    if (k.has("mpcdi") || k.has("region")) k.fail("bourke", "give either bourke or mpcdi and region, not both");
    k.reject_unknown_keys();
    try {
        read_bourke_mesh(cal.bourke_file, cal.raster_width, cal.raster_height);
    } catch (const CalibrationError& e) {
        k.fail("bourke", e.what());
    }
    return cal;
}

// The channel's MPCDI region (the package is opened to find the region, its raster and frustum)
// or its Bourke mesh.
ChannelCalibration read_calibration(const JsonReader& k, const std::string& directory,
                                    std::optional<CalibratedFrustum>& frustum) {
    if (k.has("bourke")) return read_bourke_calibration(k, directory);
    ChannelCalibration cal;
    cal.mpcdi_file = resolve_path(directory, k.string("mpcdi"));
    if (!fs::is_regular_file(cal.mpcdi_file)) k.fail("mpcdi", "file \"" + cal.mpcdi_file + "\" does not exist");
    cal.region = k.string("region");
    for (const char* name : {"pfm_rows", "v_origin", "coordinates", "warp_direction"})
        cal.reading.set(name, k.declared_choice(name));
    k.reject_unknown_keys();
    try {
        const MpcdiPackage package = MpcdiPackage::open(cal.mpcdi_file);
        for (const auto& region : package.regions())
            if (region.id == cal.region) {
                cal.raster_width = region.x_resolution, cal.raster_height = region.y_resolution;
                frustum = region.frustum;
                return cal;
            }
    } catch (const CalibrationError& e) {
        k.fail("mpcdi", e.what());
    }
    k.fail("region", "no region \"" + cal.region + "\" in " + cal.mpcdi_file);
    return cal;
}

// What every channel takes from the rest of the cluster file.
struct ChannelDefaults {
    int width = 0, height = 0;
    Transport transport = Transport::Broadcast;
    std::string directory;
    SinkConfig sinks;
    RoomConfig room;
    StereoMode stereo = StereoMode::Mono;
};

// A channel given as a screen's corners in the room: the off-axis frustum from the room's eye.
void read_channel_screen(const JsonReader& r, const RoomConfig& room, ChannelConfig& c) {
    if (r.has("orientation") || r.has("fov")) r.fail("screen", "give either screen or orientation and fov, not both");
    const JsonReader k = r.child("screen");
    PlanarScreen s;
    s.lower_left_m = k.dvec3("lower_left_m");
    s.upper_left_m = k.dvec3("upper_left_m");
    s.upper_right_m = k.dvec3("upper_right_m");
    k.reject_unknown_keys();
    try {
        const ScreenFrustum f = screen_frustum(s, room.eye_m);
        c.orientation = f.orientation, c.fov = f.fov, c.screen = s;
    } catch (const std::invalid_argument& e) {
        r.fail("screen", std::string(e.what()) + " (room.eye_m is the eye)");
    }
}

// Orientation and fov as the channel gives them, as a screen's corners, or the calibration's
// 3d-profile frustum.
void read_channel_frustum(const JsonReader& r, const ChannelDefaults& d, ChannelConfig& c) {
    std::optional<CalibratedFrustum> file_frustum;
    if (auto k = r.optional_child("calibration")) c.calibration = read_calibration(*k, d.directory, file_frustum);
    if (r.has("screen")) return read_channel_screen(r, d.room, c);
    const bool own = r.has("orientation") || r.has("fov");
    if (!own && c.calibration) {
        if (!file_frustum)
            r.fail("calibration",
                   "region \"" + c.calibration->region + "\" has no frustum (2d profile): give orientation and fov");
        c.orientation = file_frustum->orientation, c.fov = file_frustum->fov;
        c.calibration->frustum_from_file = true;
        return;
    }
    auto o = r.child("orientation");
    c.orientation.yaw_deg = o.declared_number("yaw_deg");
    c.orientation.pitch_deg = o.declared_number("pitch_deg");
    c.orientation.roll_deg = o.declared_number("roll_deg");
    o.reject_unknown_keys();
    c.fov = read_fov(r.child("fov"));
}

StereoMode read_stereo_mode(const JsonReader& r) {
    try {
        return stereo_mode_from_name(r.has("stereo") ? r.one_of("stereo", r.declared_choices("stereo")) : "mono");
    } catch (const std::invalid_argument& e) {
        r.fail("stereo", e.what());
    }
}

// The channel's stereo mode (its own, or the output section's), and what it cannot be combined with.
void read_channel_stereo(const JsonReader& r, const ChannelDefaults& d, ChannelConfig& c) {
    c.stereo = r.has("stereo") ? read_stereo_mode(r) : d.stereo;
    if (c.stereo == StereoMode::Mono) return;
    const char* key = r.has("stereo") ? "stereo" : "id";
    if (c.calibration)
        r.fail(key,
               "a channel with a warp calibration shows one eye (stereo mono, left or right) for now; its frame "
               "would hold two images where the warp expects one");
    const bool half = c.stereo == StereoMode::SideBySideHalf || c.stereo == StereoMode::TopBottomHalf;
    if (half && (c.width % 2 || c.height % 2))
        r.fail(key, "a half-resolution stereo frame needs an even width and height, not " + std::to_string(c.width) +
                        "x" + std::to_string(c.height));
}

ChannelConfig read_channel(const JsonReader& r, const ChannelDefaults& d) {
    ChannelConfig c;
    c.output = d.sinks;
    c.id = static_cast<int>(r.declared_integer("id"));
    c.name = r.string("name", "channel" + std::to_string(c.id));
    for (char ch : c.name)
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_'))
            r.fail("name", "\"" + c.name + "\" may hold only letters, digits, '-' and '_' (it names a folder)");
    read_channel_frustum(r, d, c);
    c.width = static_cast<int>(r.declared_integer("width", d.width));
    c.height = static_cast<int>(r.declared_integer("height", d.height));
    if (d.transport == Transport::Unicast) {
        c.unicast_address = r.string("unicast_address");
        check_host_port(r, "unicast_address", c.unicast_address);
    } else {
        c.unicast_address = r.string("unicast_address", "");
        if (!c.unicast_address.empty()) check_host_port(r, "unicast_address", c.unicast_address);
    }
    if (auto o = r.optional_child("output")) {
        c.output = read_sinks(*o, d.sinks);
        o->reject_unknown_keys();
    }
    read_channel_stereo(r, d, c);
    r.reject_unknown_keys();
    return c;
}

std::string existing_file(const JsonReader& r, const std::string& directory, const std::string& key) {
    std::string p = resolve_path(directory, r.string(key));
    if (!fs::is_regular_file(p)) r.fail(key, "file \"" + p + "\" does not exist");
    return p;
}

HeadTrackingConfig read_tracking(const JsonReader& t) {
    HeadTrackingConfig c;
    const std::string source = t.declared_choice("source");
    c.source = source == "dtrack" ? TrackingSource::Dtrack : TrackingSource::Fixed;
    c.address = ipv4(t, "address");
    c.port = static_cast<uint16_t>(t.declared_integer("port"));
    c.body = static_cast<int>(t.declared_integer("body"));
    c.mounting.axes = tracker_axes_from_name(t.declared_choice("axes"));
    c.mounting.origin_m = t.optional_dvec3("origin_m").value_or(glm::dvec3(0.0));
    c.fresh_s = t.declared_number("fresh_s");
    c.timeout_s = t.declared_number("timeout_s");
    if (c.timeout_s < c.fresh_s)
        t.fail("timeout_s", "must not be shorter than fresh_s (" + std::to_string(c.fresh_s) + ")");
    const std::string filter = t.declared_choice("filter");
    c.filter = filter == "smooth" ? HeadFilter::Smooth : filter == "predict" ? HeadFilter::Predict : HeadFilter::None;
    c.smoothing_s = t.declared_number("smoothing_s");
    c.prediction_s = t.declared_number("prediction_s");
    t.reject_unknown_keys();
    return c;
}

RoomConfig read_room(const JsonReader& r) {
    RoomConfig room;
    room.eye_m = r.optional_dvec3("eye_m").value_or(glm::dvec3(0.0));
    room.origin_m = r.optional_dvec3("origin_m");
    room.scale = r.declared_number("scale");
    room.eye_separation_m = r.declared_number("eye_separation_m");
    room.tracking = read_tracking(r.section("tracking"));
    r.reject_unknown_keys();
    return room;
}

DomeConfig read_dome(const JsonReader& d) {
    DomeConfig dome;
    dome.fov_deg = d.declared_number("fov_deg");
    dome.tilt_deg = d.declared_number("tilt_deg");
    dome.require_full_coverage = d.declared_boolean("require_full_coverage");
    d.reject_unknown_keys();
    return dome;
}

AutoExposureConfig read_auto_exposure(const JsonReader& a) {
    AutoExposureConfig ae;
    ae.enabled = a.declared_boolean("enabled");
    ae.key = a.declared_number("key");
    ae.key_follows_adaptation = a.declared_boolean("key_follows_adaptation");
    ae.light_adaptation_s = a.declared_number("light_adaptation_s");
    ae.dark_adaptation_s = a.declared_number("dark_adaptation_s");
    ae.night_vision = a.declared_boolean("night_vision");
    ae.acuity_blur = a.declared_boolean("acuity_blur");
    ae.min_exposure = a.declared_number("min_exposure");
    ae.max_exposure = a.declared_number("max_exposure");
    if (ae.min_exposure > ae.max_exposure)
        a.fail("min_exposure", "must not exceed max_exposure (" + std::to_string(ae.max_exposure) + ")");
    a.reject_unknown_keys();
    return ae;
}

// The output section, and the default channel size it gives.
OutputConfig read_output(const JsonReader& o, int& default_w, int& default_h) {
    OutputConfig out;
    out.formats = o.strings("formats", o.declaration("formats").at("default").get<std::vector<std::string>>());
    const std::vector<std::string> allowed = o.declared_choices("formats");
    std::string quoted, listed;
    for (const auto& a : allowed) {
        quoted += (quoted.empty() ? "\"" : ", \"") + a + "\"";
        listed += (listed.empty() ? "" : ", ") + a;
    }
    if (out.formats.empty()) o.fail("formats", "name at least one of " + quoted);
    for (size_t i = 0; i < out.formats.size(); ++i)
        if (std::find(allowed.begin(), allowed.end(), out.formats[i]) == allowed.end())
            throw ConfigError(o.file(), o.field("formats") + "[" + std::to_string(i) + "]",
                              "\"" + out.formats[i] + "\" is not one of: " + listed);
    out.domemaster_size = static_cast<int>(o.declared_integer("domemaster_size"));
    out.exposure = o.declared_number("exposure");
    if (auto a = o.optional_child("auto_exposure")) out.auto_exposure = read_auto_exposure(*a);
    out.sink = read_sinks(o, SinkConfig{});
    out.stereo = read_stereo_mode(o);
    default_w = static_cast<int>(o.declared_integer("width"));
    default_h = static_cast<int>(o.declared_integer("height"));
    o.reject_unknown_keys();
    return out;
}

// input.buttons: {"index": action}; replaces the default map.
std::map<int, std::string> read_buttons(const JsonReader& b) {
    std::map<int, std::string> actions;
    for (const auto& [key, value] : b.raw().items()) {
        int index = -1;
        if (all_digits(key) && key.size() < 9) index = std::stoi(key);
        if (index < 0 || index > 31) b.fail(key, "a button is named by its index, 0..31");
        actions[index] = b.one_of(key, button_action_names());
    }
    return actions;
}

InputConfig read_input(const JsonReader& in, const std::string& directory) {
    InputConfig ic;
    ic.usb = in.declared_boolean("usb");
    if (in.has("device_table")) ic.device_table_file = existing_file(in, directory, "device_table");
    ic.dead_zone = in.declared_number("dead_zone");
    ic.smoothing_s = in.declared_number("smoothing_s");
    ic.speed_per_altitude = in.declared_number("speed_per_altitude");
    ic.min_speed_m_s = in.declared_number("min_speed_m_s");
    ic.turn_rate_deg_s = in.declared_number("turn_rate_deg_s");
    ic.orbit_rate_deg_s = in.declared_number("orbit_rate_deg_s");
    ic.goto_seconds = in.declared_number("goto_seconds");
    ic.takeover = in.declared_boolean("takeover");
    // Absent: the declared default map, read like a given one.
    const nlohmann::json& default_buttons = in.declaration("buttons").at("default");
    auto b = in.optional_child("buttons");
    ic.button_actions = read_buttons(b ? *b : JsonReader(default_buttons, in.file(), in.field("buttons")));
    in.reject_unknown_keys();
    return ic;
}

std::vector<ChannelConfig> read_channels(const JsonReader& r, const ChannelDefaults& defaults) {
    auto channels = r.array("channels");
    if (channels.empty()) r.fail("channels", "at least one channel is required");
    std::set<int> ids;
    std::set<std::string> names;
    std::vector<ChannelConfig> out;
    for (auto& ch : channels) {
        ChannelConfig c = read_channel(ch, defaults);
        if (!ids.insert(c.id).second) ch.fail("id", "channel id " + std::to_string(c.id) + " is used twice");
        if (!names.insert(c.name).second) ch.fail("name", "channel name \"" + c.name + "\" is used twice");
        out.push_back(c);
    }
    return out;
}

void check_coverage(const ClusterConfig& cfg, const std::string& file) {
    if (!cfg.dome.require_full_coverage) return;
    if (auto hole = find_coverage_hole(cfg.dome, cfg.channels)) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "the channel frusta leave a hole in the dome at azimuth %.1f deg, elevation %.1f deg "
                      "(widen a channel's fov or set dome.require_full_coverage to false)",
                      hole->azimuth_deg, hole->elevation_deg);
        throw ConfigError(file, "channels", buf);
    }
}

}  // namespace

bool SinkConfig::has(const std::string& sink) const {
    return std::find(sinks.begin(), sinks.end(), sink) != sinks.end();
}

const std::vector<std::string>& button_action_names() {
    static const std::vector<std::string> names = {"next_mode", "toggle_pause",  "play",
                                                   "stop",      "orbit_nearest", "none"};
    return names;
}

ClusterConfig load_cluster_config(const std::string& file_in) {
    std::error_code ec;
    fs::path abs = fs::absolute(file_in, ec);
    ClusterConfig cfg;
    cfg.file = abs.lexically_normal().string();
    cfg.directory = abs.parent_path().string();
    const nlohmann::json doc = JsonReader::parse_file(file_in);
    JsonReader r(doc, file_in, &config_schema("cluster"));

    cfg.cluster_id = static_cast<uint32_t>(r.declared_integer("cluster_id"));
    cfg.key_file = existing_file(r, cfg.directory, "key_file");
    cfg.scene_file = existing_file(r, cfg.directory, "scene");
    cfg.show_file = existing_file(r, cfg.directory, "show");
    cfg.frame_rate_hz = r.declared_number("frame_rate_hz");
    cfg.egl_device = static_cast<int>(r.declared_integer("egl_device"));
    cfg.network = read_network(r.section("network"));
    cfg.dome = read_dome(r.section("dome"));
    cfg.room = read_room(r.section("room"));
    ChannelDefaults defaults;
    cfg.output = read_output(r.section("output"), defaults.width, defaults.height);
    cfg.input = read_input(r.section("input"), cfg.directory);
    defaults.transport = cfg.network.transport;
    defaults.directory = cfg.directory;
    defaults.sinks = cfg.output.sink;
    defaults.stereo = cfg.output.stereo;
    defaults.room = cfg.room;
    cfg.channels = read_channels(r, defaults);
    r.reject_unknown_keys();
    check_coverage(cfg, file_in);
    return cfg;
}

std::optional<CoverageHole> find_coverage_hole(const DomeConfig& dome, const std::vector<ChannelConfig>& channels,
                                               int samples) {
    FisheyeMapping fish(dome.fov_deg);
    std::vector<ChannelFrustum> frusta;
    for (const auto& c : channels) frusta.push_back(c.frustum());
    auto covered = [&](const glm::dvec3& d) {
        for (const auto& f : frusta)
            if (f.contains(d)) return true;
        return false;
    };
    auto hole_at = [&](const glm::dvec3& d) {
        // Dome frame: apex +Y, front -Z, right +X.
        CoverageHole h;
        h.elevation_deg = glm::degrees(std::asin(std::clamp(d.y, -1.0, 1.0)));
        h.azimuth_deg = glm::degrees(std::atan2(d.x, -d.z));
        return h;
    };
    for (int j = 0; j < samples; ++j) {
        for (int i = 0; i < samples; ++i) {
            glm::dvec2 uv(-1.0 + 2.0 * i / (samples - 1), -1.0 + 2.0 * j / (samples - 1));
            auto d = fish.uv_to_direction(uv);
            if (d && !covered(*d)) return hole_at(*d);
        }
    }
    // The rim itself, densely.
    for (int k = 0; k < samples * 8; ++k) {
        double a = 2.0 * M_PI * k / (samples * 8);
        auto d = fish.uv_to_direction(glm::dvec2(std::cos(a), std::sin(a)) * (1.0 - 1e-9));
        if (d && !covered(*d)) return hole_at(*d);
    }
    return std::nullopt;
}

ChannelFrustum ChannelConfig::frustum_seen_from(const glm::dvec3& eye_room_m) const {
    if (!screen) return frustum();
    try {
        return ChannelFrustum(orientation, screen_frustum(*screen, eye_room_m).fov, width, height);
    } catch (const std::invalid_argument&) {
        return frustum();
    }
}

}  // namespace cupola
