#include "config/cluster_config.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>

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

std::string ipv4(const JsonReader& r, const std::string& key, const std::string& fallback) {
    std::string s = r.string(key, fallback);
    in_addr a{};
    if (inet_pton(AF_INET, s.c_str(), &a) != 1) r.fail(key, "\"" + s + "\" is not an IPv4 address");
    return s;
}

void check_host_port(const JsonReader& r, const std::string& key, const std::string& s) {
    auto colon = s.rfind(':');
    in_addr a{};
    if (colon == std::string::npos || inet_pton(AF_INET, s.substr(0, colon).c_str(), &a) != 1)
        r.fail(key, "\"" + s + "\" is not of the form IPv4:port");
    try {
        size_t used = 0;
        int port = std::stoi(s.substr(colon + 1), &used);
        if (used != s.size() - colon - 1 || port < 1 || port > 65535) throw std::invalid_argument("port");
    } catch (const std::exception&) {
        r.fail(key, "\"" + s + "\" has no valid port (1..65535)");
    }
}

NetworkConfig read_network(const JsonReader& r) {
    NetworkConfig n;
    std::string t = r.one_of("transport", {"multicast", "broadcast", "unicast"}, "multicast");
    n.transport = t == "multicast"   ? Transport::Multicast
                  : t == "broadcast" ? Transport::Broadcast
                                     : Transport::Unicast;
    n.multicast_group = ipv4(r, "multicast_group", n.multicast_group);
    if (n.transport == Transport::Multicast) {
        in_addr a{};
        inet_pton(AF_INET, n.multicast_group.c_str(), &a);
        uint32_t h = ntohl(a.s_addr);
        if ((h >> 28) != 0xE)
            r.fail("multicast_group", "\"" + n.multicast_group + "\" is not a multicast address (224.0.0.0/4)");
    }
    n.interface_address = ipv4(r, "interface_address", n.interface_address);
    n.broadcast_address = ipv4(r, "broadcast_address", n.broadcast_address);
    n.master_address = ipv4(r, "master_address", n.master_address);
    n.snapshot_port = static_cast<uint16_t>(r.integer_in("snapshot_port", 1, 65535, n.snapshot_port));
    n.report_port = static_cast<uint16_t>(r.integer_in("report_port", 1, 65535, n.report_port));
    if (n.report_port == n.snapshot_port) r.fail("report_port", "must differ from snapshot_port");
    n.max_datagram_bytes = static_cast<int>(r.integer_in("max_datagram_bytes", 256, 65000, n.max_datagram_bytes));
    n.channel_timeout_ms = static_cast<int>(r.integer_in("channel_timeout_ms", 10, 600000, n.channel_timeout_ms));
    n.resend_interval_ms = static_cast<int>(r.integer_in("resend_interval_ms", 1, 60000, n.resend_interval_ms));
    n.hello_wait_ms = static_cast<int>(r.integer_in("hello_wait_ms", 0, 600000, n.hello_wait_ms));
    n.strict_key_permissions = r.boolean("strict_key_permissions", n.strict_key_permissions);
    r.reject_unknown_keys();
    return n;
}

ChannelConfig read_channel(const JsonReader& r, int default_w, int default_h, Transport transport) {
    ChannelConfig c;
    c.id = static_cast<int>(r.integer_in("id", 0, 4095));
    c.name = r.string("name", "channel" + std::to_string(c.id));
    for (char ch : c.name)
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_'))
            r.fail("name", "\"" + c.name + "\" may hold only letters, digits, '-' and '_' (it names a folder)");
    auto o = r.child("orientation");
    c.orientation.yaw_deg = o.number_in("yaw_deg", -360, 360, 0);
    c.orientation.pitch_deg = o.number_in("pitch_deg", -90, 90, 0);
    c.orientation.roll_deg = o.number_in("roll_deg", -360, 360, 0);
    o.reject_unknown_keys();
    auto f = r.child("fov");
    c.fov.left_deg = f.number_in("left_deg", -89.0, 89.0);
    c.fov.right_deg = f.number_in("right_deg", -89.0, 89.0);
    c.fov.up_deg = f.number_in("up_deg", -89.0, 89.0);
    c.fov.down_deg = f.number_in("down_deg", -89.0, 89.0);
    if (c.fov.left_deg + c.fov.right_deg <= 0.1) f.fail("right_deg", "left_deg + right_deg must be positive");
    if (c.fov.up_deg + c.fov.down_deg <= 0.1) f.fail("up_deg", "up_deg + down_deg must be positive");
    f.reject_unknown_keys();
    c.width = static_cast<int>(r.integer_in("width", 8, 16384, default_w));
    c.height = static_cast<int>(r.integer_in("height", 8, 16384, default_h));
    if (transport == Transport::Unicast) {
        c.unicast_address = r.string("unicast_address");
        check_host_port(r, "unicast_address", c.unicast_address);
    } else {
        c.unicast_address = r.string("unicast_address", "");
        if (!c.unicast_address.empty()) check_host_port(r, "unicast_address", c.unicast_address);
    }
    r.reject_unknown_keys();
    return c;
}

}  // namespace

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
    JsonReader r(doc, file_in, "");

    cfg.cluster_id = static_cast<uint32_t>(r.integer_in("cluster_id", 0, 0xFFFFFFFFLL));
    auto file_field = [&](const std::string& key) {
        std::string p = resolve_path(cfg.directory, r.string(key));
        if (!fs::is_regular_file(p)) r.fail(key, "file \"" + p + "\" does not exist");
        return p;
    };
    cfg.key_file = file_field("key_file");
    cfg.scene_file = file_field("scene");
    cfg.show_file = file_field("show");
    cfg.frame_rate_hz = r.number_in("frame_rate_hz", 0, 1000, 0);
    cfg.egl_device = static_cast<int>(r.integer_in("egl_device", -1, 64, -1));

    if (auto n = r.optional_child("network")) cfg.network = read_network(*n);

    if (auto d = r.optional_child("dome")) {
        cfg.dome.fov_deg = d->number_in("fov_deg", 1, 360, 180);
        cfg.dome.tilt_deg = d->number_in("tilt_deg", -90, 90, 0);
        cfg.dome.require_full_coverage = d->boolean("require_full_coverage", true);
        d->reject_unknown_keys();
    }

    int default_w = 512, default_h = 512;
    if (auto o = r.optional_child("output")) {
        cfg.output.formats = o->strings("formats", cfg.output.formats);
        if (cfg.output.formats.empty()) o->fail("formats", "name at least one of \"png\", \"exr\"");
        for (size_t i = 0; i < cfg.output.formats.size(); ++i)
            if (cfg.output.formats[i] != "png" && cfg.output.formats[i] != "exr")
                throw ConfigError(file_in, o->field("formats") + "[" + std::to_string(i) + "]",
                                  "\"" + cfg.output.formats[i] + "\" is not one of: png, exr");
        cfg.output.domemaster_size = static_cast<int>(o->integer_in("domemaster_size", 16, 16384, 1024));
        cfg.output.exposure = o->number_in("exposure", 1e-12, 1e6, 1.0);
        if (auto a = o->optional_child("auto_exposure")) {
            AutoExposureConfig& ae = cfg.output.auto_exposure;
            ae.enabled = a->boolean("enabled", true);
            ae.key = a->number_in("key", 1e-6, 1e3, ae.key);
            ae.min_exposure = a->number_in("min_exposure", 1e-15, 1e9, ae.min_exposure);
            ae.max_exposure = a->number_in("max_exposure", 1e-15, 1e9, ae.max_exposure);
            if (ae.min_exposure > ae.max_exposure)
                a->fail("min_exposure", "must not exceed max_exposure (" + std::to_string(ae.max_exposure) + ")");
            a->reject_unknown_keys();
        }
        default_w = static_cast<int>(o->integer_in("width", 8, 16384, default_w));
        default_h = static_cast<int>(o->integer_in("height", 8, 16384, default_h));
        o->reject_unknown_keys();
    }

    if (auto in = r.optional_child("input")) {
        InputConfig& ic = cfg.input;
        ic.usb = in->boolean("usb", ic.usb);
        if (in->has("device_table")) {
            ic.device_table_file = resolve_path(cfg.directory, in->string("device_table"));
            if (!fs::is_regular_file(ic.device_table_file))
                in->fail("device_table", "file \"" + ic.device_table_file + "\" does not exist");
        }
        ic.dead_zone = in->number_in("dead_zone", 0.0, 0.9, ic.dead_zone);
        ic.smoothing_s = in->number_in("smoothing_s", 0.0, 10.0, ic.smoothing_s);
        ic.speed_per_altitude = in->number_in("speed_per_altitude", 1e-6, 100.0, ic.speed_per_altitude);
        ic.min_speed_m_s = in->number_in("min_speed_m_s", 0.0, 1e9, ic.min_speed_m_s);
        ic.turn_rate_deg_s = in->number_in("turn_rate_deg_s", 0.1, 3600.0, ic.turn_rate_deg_s);
        ic.orbit_rate_deg_s = in->number_in("orbit_rate_deg_s", 0.1, 3600.0, ic.orbit_rate_deg_s);
        ic.goto_seconds = in->number_in("goto_seconds", 0.0, 600.0, ic.goto_seconds);
        ic.takeover = in->boolean("takeover", ic.takeover);
        if (auto b = in->optional_child("buttons")) {
            ic.button_actions.clear();
            for (const auto& [key, value] : b->raw().items()) {
                int index = -1;
                try {
                    size_t used = 0;
                    index = std::stoi(key, &used);
                    if (used != key.size() || index < 0 || index > 31) index = -1;
                } catch (const std::exception&) {}
                if (index < 0) b->fail(key, "a button is named by its index, 0..31");
                ic.button_actions[index] = b->one_of(key, button_action_names());
            }
        }
        in->reject_unknown_keys();
    }

    auto channels = r.array("channels");
    if (channels.empty()) r.fail("channels", "at least one channel is required");
    std::set<int> ids;
    std::set<std::string> names;
    for (auto& ch : channels) {
        ChannelConfig c = read_channel(ch, default_w, default_h, cfg.network.transport);
        if (!ids.insert(c.id).second) ch.fail("id", "channel id " + std::to_string(c.id) + " is used twice");
        if (!names.insert(c.name).second) ch.fail("name", "channel name \"" + c.name + "\" is used twice");
        cfg.channels.push_back(c);
    }
    r.reject_unknown_keys();

    if (cfg.dome.require_full_coverage) {
        if (auto hole = find_coverage_hole(cfg.dome, cfg.channels)) {
            char buf[200];
            std::snprintf(buf, sizeof buf,
                          "the channel frusta leave a hole in the dome at azimuth %.1f deg, elevation %.1f deg "
                          "(widen a channel's fov or set dome.require_full_coverage to false)",
                          hole->azimuth_deg, hole->elevation_deg);
            throw ConfigError(file_in, "channels", buf);
        }
    }
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

}  // namespace cupola
