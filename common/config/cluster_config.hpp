#pragma once
// The cluster configuration: network, dome, output and the channels (one slave process each).
// Loaded from JSON by load_cluster_config(); every mistake throws ConfigError naming file and field.
// The file format, each field's default, range and meaning: configs/schema/cluster.schema.json
// (docs/CONFIG.md is written from it). The initialisers below are those defaults, for code that
// builds a config without a file; test_config_schema checks they match the schema.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <optional>

#include "calibration/mpcdi_reading.hpp"
#include "projection/channel_frustum.hpp"
#include "projection/planar_screen.hpp"
#include "projection/stereo_mode.hpp"
#include "tracking/head_tracking_config.hpp"

namespace cupola {

enum class Transport { Multicast, Broadcast, Unicast };

struct NetworkConfig {
    Transport transport = Transport::Multicast;
    std::string multicast_group = "239.255.76.67";
    std::string interface_address = "127.0.0.1";  // multicast interface / bind address for slaves
    std::string broadcast_address = "127.255.255.255";
    std::string master_address = "127.0.0.1";  // where slaves send their reports
    uint16_t snapshot_port = 47600;            // master -> slaves (multicast, broadcast)
    uint16_t report_port = 47601;              // slaves -> master
    int max_datagram_bytes = 1400;             // fragments snapshots above this
    int channel_timeout_ms = 2000;             // silent channel is dropped after this
    int first_frame_timeout_ms = 10000;        // ... or this, before its first report (shader compiles)
    int resend_interval_ms = 100;              // snapshot re-sent while the barrier waits
    int hello_wait_ms = 15000;                 // master waits this long for all channels at start
    bool strict_key_permissions = false;       // a key file open to every user: error, not warning
    bool swap_lock = true;                     // two-phase frame: slaves show frame N on the master's present
};

struct DomeConfig {
    double fov_deg = 180.0;
    double tilt_deg = 0.0;
    bool require_full_coverage = true;  // a hole between channel frusta is a config error
};

// Cluster-wide automatic exposure, decided by the master from the shared scene state (see
// common/atmosphere/auto_exposure.hpp and common/exposure/): the eye adapts to the log-average
// luminance of the lit view, and exposure = key / adapted luminance, clamped.
struct AutoExposureConfig {
    bool enabled = false;
    double key = 0.18;                   // display value given to the adapted luminance
    bool key_follows_adaptation = true;  // the key falls at night (exposure/eye_adaptation.hpp)
    double light_adaptation_s = 1.0;     // time constant toward a brighter view
    double dark_adaptation_s = 120.0;    // time constant toward a darker view
    bool night_vision = false;           // colour fades and turns blue at night (shaders/shared/night_vision.glsl)
    bool acuity_blur = false;            // with night_vision: detail blurs as acuity falls (night_acuity.glsl)
    double min_exposure = 1e-9;
    double max_exposure = 1e3;  // reached on a black (night, no-atmosphere) sky
};

// The live sinks' settings (slave/output/): the window sink on X11, the KMS sink on DRM/GBM.
struct WindowOutputConfig {
    std::string display;      // X11 display name, e.g. ":0"
    std::string output_name;  // RandR output; empty: the whole screen
    bool fullscreen = true;   // false: a window of the projector raster's size
};

struct KmsOutputConfig {
    std::string device = "/dev/dri/card0";
    std::string connector;  // e.g. "HDMI-A-1"; empty: the first connected one
    int mode_width = 0;     // 0: the connector's preferred mode
    int mode_height = 0;
    double mode_refresh_hz = 0.0;  // 0: any refresh at that size (the highest)
};

// Where a channel's frames go: "files", "window" and/or "kms" (window and kms exclude each other).
struct SinkConfig {
    std::vector<std::string> sinks = {"files"};
    WindowOutputConfig window;
    KmsOutputConfig kms;
    bool has(const std::string& sink) const;
};

struct OutputConfig {
    std::vector<std::string> formats = {"png"};  // "png" (8-bit sRGB) and/or "exr" (half float, linear)
    int domemaster_size = 1024;
    double exposure = 1.0;  // fixed exposure (scene units -> display), unless auto_exposure
    AutoExposureConfig auto_exposure;
    SinkConfig sink;                       // cluster-wide; a channel's own output section replaces parts of it
    StereoMode stereo = StereoMode::Mono;  // every channel's, unless it gives its own
};

// Live navigation on the master (master/input, master/navigation): the USB devices and how they
// fly the camera. The numbers are at full deflection of an axis.
struct InputConfig {
    bool usb = true;                  // look for USB navigation devices (none found: nothing happens)
    std::string device_table_file;    // optional JSON device table (resolved path), before the defaults
    double dead_zone = 0.08;          // fraction of an axis' travel that counts as rest
    double smoothing_s = 0.12;        // time constant of the input smoothing (0: none)
    double speed_per_altitude = 0.5;  // translation per second, as a fraction of the altitude
    double min_speed_m_s = 1.0;       // translation floor (on foot)
    double turn_rate_deg_s = 45.0;    // looking around
    double orbit_rate_deg_s = 30.0;   // orbiting a body
    double goto_seconds = 4.0;        // duration of a "goto" flight
    bool takeover = true;             // touching a device during a show stops it and hands over the camera
    // What a device button does when pressed (button index -> action, see button_action_names()).
    std::map<int, std::string> button_actions = {{0, "next_mode"}, {1, "toggle_pause"}};
};

// "next_mode" (orbit -> free fly -> surface walk -> orbit), "toggle_pause", "play" (resume the
// show), "stop" (leave the show), "orbit_nearest" (orbit the nearest body), "none".
const std::vector<std::string>& button_action_names();

// The projector a channel feeds: a region of an MPCDI package (common/calibration/mpcdi_package)
// or a Paul Bourke mesh (common/calibration/bourke_mesh); read by calibration/channel_warp.hpp.
struct ChannelCalibration {
    std::string mpcdi_file;  // resolved path; empty for a Bourke mesh
    std::string region;
    std::string bourke_file;  // resolved path of a Paul Bourke mesh, instead of an MPCDI region
    MpcdiReading reading;     // the switches where the standard is ambiguous
    int raster_width = 0;     // the projector raster, from the package (a Bourke mesh: from the config)
    int raster_height = 0;
    bool frustum_from_file = false;  // the channel's orientation and fov are the region's frustum
};

// The room of a VR wall or a CAVE: the dome frame's axes in metres (x right, y up, z toward the
// back); where the viewer's eye is when nothing tracks it (channels given as screens are seen from
// the eye); the room point the scene camera is at, and how many scene metres a room metre is; and
// what follows the viewer's head.
struct RoomConfig {
    glm::dvec3 eye_m{0.0};
    std::optional<glm::dvec3> origin_m;  // none: eye_m
    double scale = 1.0;                  // scene metres per room metre
    double eye_separation_m = 0.064;     // between the viewer's eyes (stereo)
    HeadTrackingConfig tracking;
    glm::dvec3 origin() const { return origin_m.value_or(eye_m); }
    // How far an eye at this room point is from the scene's camera, in scene metres along the
    // room's (the dome frame's) axes.
    glm::dvec3 scene_offset_m(const glm::dvec3& eye_room_m) const { return (eye_room_m - origin()) * scale; }
};

struct ChannelConfig {
    int id = 0;
    std::string name;
    EulerDeg orientation;
    FovDeg fov;
    std::optional<PlanarScreen> screen;    // given as a flat screen's corners: orientation and fov follow
    StereoMode stereo = StereoMode::Mono;  // one eye, or both packed into its frame
    std::optional<ChannelCalibration> calibration;
    int width = 512;
    int height = 512;
    std::string unicast_address;  // "host:port", used with the unicast transport
    SinkConfig output;            // the cluster's output.sink/window/kms, with this channel's own keys
    ChannelFrustum frustum() const { return ChannelFrustum(orientation, fov, width, height); }
    // The frustum as an eye at this room point sees it: a screen's follows the eye (Kooima 2008);
    // any other channel's is its own. An eye that is not in front of the screen (a head through the
    // wall) keeps the configured frustum.
    ChannelFrustum frustum_seen_from(const glm::dvec3& eye_room_m) const;
};

struct ClusterConfig {
    std::string file;       // absolute path of the config file
    std::string directory;  // its directory; relative paths resolve against it
    uint32_t cluster_id = 1;
    std::string key_file;        // resolved path
    std::string scene_file;      // resolved path
    std::string show_file;       // resolved path
    double frame_rate_hz = 0.0;  // 0: as fast as the barrier allows
    int egl_device = -1;         // -1: first usable device, then Mesa surfaceless
    NetworkConfig network;
    DomeConfig dome;
    RoomConfig room;
    OutputConfig output;
    InputConfig input;
    std::vector<ChannelConfig> channels;

    const ChannelConfig& channel(int id) const;  // throws std::out_of_range naming the id
};

ClusterConfig load_cluster_config(const std::string& file);

// Direction (dome frame) of the first point of the dome image circle that no channel covers, or
// nothing when the channels cover the whole dome. samples: grid points across the diameter.
struct CoverageHole {
    double azimuth_deg;    // 0 = front, 90 = right
    double elevation_deg;  // 90 = apex
};
std::optional<CoverageHole> find_coverage_hole(const DomeConfig& dome, const std::vector<ChannelConfig>& channels,
                                               int samples = 121);

std::string resolve_path(const std::string& base_dir, const std::string& path);

}  // namespace cupola
