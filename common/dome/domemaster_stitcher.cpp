#include "dome/domemaster_stitcher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>
#include <thread>

#include "calibration/channel_warp.hpp"
#include "dome/acuity_blur.hpp"
#include "dome/projector_frame_stitcher.hpp"
#include "projection/fisheye.hpp"

namespace cupola {

namespace fs = std::filesystem;

namespace {

double smoothstep01(double t) {
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Runs body(row) for every row in [0, rows), on at most two threads.
void for_rows(int rows, const std::function<void(int)>& body) {
    const unsigned hw = std::thread::hardware_concurrency();
    if (rows < 64 || hw < 2) {
        for (int y = 0; y < rows; ++y) body(y);
        return;
    }
    std::thread second([&] {
        for (int y = 1; y < rows; y += 2) body(y);
    });
    for (int y = 0; y < rows; y += 2) body(y);
    second.join();
}

void check_size(int size) {
    if (size <= 0 || size > 32768)
        throw std::invalid_argument("domemaster size " + std::to_string(size) + " is not in 1..32768");
}

Image blank(int size) {
    Image out;
    out.width = size;
    out.height = size;
    out.rgba.assign(static_cast<size_t>(size) * size * 4, 0.0f);
    return out;
}

void check_image(const ChannelFrustum& f, const Image& im, size_t index) {
    if (im.width != f.width() || im.height != f.height() ||
        im.rgba.size() != static_cast<size_t>(im.width) * im.height * 4)
        throw std::invalid_argument("channel " + std::to_string(index) + ": image is " + std::to_string(im.width) +
                                    "x" + std::to_string(im.height) + " but its frustum is " +
                                    std::to_string(f.width()) + "x" + std::to_string(f.height()));
}

// The size, and one image per channel of its frustum's size (null: none).
void check_inputs(const char* what, const std::vector<ChannelFrustum>& channels,
                  const std::vector<const Image*>& images, int size) {
    check_size(size);
    if (channels.size() != images.size())
        throw std::invalid_argument(std::string(what) + ": " + std::to_string(channels.size()) + " channels but " +
                                    std::to_string(images.size()) + " images");
    for (size_t i = 0; i < channels.size(); ++i)
        if (images[i]) check_image(channels[i], *images[i], i);
}

}  // namespace

void sample_bilinear(const Image& image, double x, double y, float out[4]) {
    const double fx = x - 0.5, fy = y - 0.5;
    const double x0f = std::floor(fx), y0f = std::floor(fy);
    const double ax = fx - x0f, ay = fy - y0f;
    const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    const int xa = std::clamp(x0, 0, image.width - 1), xb = std::clamp(x0 + 1, 0, image.width - 1);
    const int ya = std::clamp(y0, 0, image.height - 1), yb = std::clamp(y0 + 1, 0, image.height - 1);
    const float* p00 = image.pixel(xa, ya);
    const float* p10 = image.pixel(xb, ya);
    const float* p01 = image.pixel(xa, yb);
    const float* p11 = image.pixel(xb, yb);
    const double w00 = (1 - ax) * (1 - ay), w10 = ax * (1 - ay), w01 = (1 - ax) * ay, w11 = ax * ay;
    for (int c = 0; c < 4; ++c) out[c] = static_cast<float>(w00 * p00[c] + w10 * p10[c] + w01 * p01[c] + w11 * p11[c]);
}

Image stitch_domemaster(const DomeConfig& dome, const std::vector<ChannelFrustum>& channels,
                        const std::vector<const Image*>& images, int size, double feather_px) {
    check_inputs("stitch_domemaster", channels, images, size);

    const FisheyeMapping fish(dome.fov_deg);
    Image out = blank(size);
    for_rows(size, [&](int y) {
        std::vector<double> weight(channels.size());
        std::vector<glm::dvec2> where(channels.size());
        for (int x = 0; x < size; ++x) {
            const glm::dvec2 uv = FisheyeMapping::pixel_to_uv(glm::dvec2(x + 0.5, y + 0.5), size);
            const auto dir = fish.uv_to_direction(uv);
            if (!dir) continue;  // outside the circle: black, alpha 0
            double total = 0.0;
            int covering = 0;
            for (size_t i = 0; i < channels.size(); ++i) {
                weight[i] = -1.0;  // not covering
                if (!images[i]) continue;
                const auto p = channels[i].dome_direction_to_pixel(*dir);
                if (!p) continue;
                const double d = channels[i].edge_distance_px(*p);
                if (d < 0.0) continue;
                where[i] = *p;
                weight[i] = feather_px > 0.0 ? smoothstep01(d / feather_px) : 1.0;
                total += weight[i];
                ++covering;
            }
            if (covering == 0) continue;  // a hole in the coverage: black, alpha 0
            // Every covering channel exactly on its edge: equal weights rather than 0/0.
            const bool equal = total <= 1e-12;
            const double norm = equal ? 1.0 / covering : 1.0 / total;
            double acc[3] = {0.0, 0.0, 0.0};
            for (size_t i = 0; i < channels.size(); ++i) {
                if (weight[i] < 0.0) continue;
                const double w = (equal ? 1.0 : weight[i]) * norm;
                if (w == 0.0) continue;
                float s[4];
                sample_bilinear(*images[i], where[i].x, where[i].y, s);
                for (int c = 0; c < 3; ++c) acc[c] += w * s[c];
            }
            float* o = out.pixel(x, y);
            for (int c = 0; c < 3; ++c) o[c] = static_cast<float>(acc[c]);
            o[3] = 1.0f;
        }
    });
    return out;
}

Image sum_domemaster(const DomeConfig& dome, const std::vector<ChannelFrustum>& channels,
                     const std::vector<const Image*>& images, int size) {
    check_inputs("sum_domemaster", channels, images, size);
    const FisheyeMapping fish(dome.fov_deg);
    Image out = blank(size);
    for_rows(size, [&](int y) {
        for (int x = 0; x < size; ++x) {
            const auto dir = fish.uv_to_direction(FisheyeMapping::pixel_to_uv(glm::dvec2(x + 0.5, y + 0.5), size));
            if (!dir) continue;  // outside the circle: black, alpha 0
            float* o = out.pixel(x, y);
            for (size_t i = 0; i < channels.size(); ++i) {
                const auto p = images[i] ? channels[i].dome_direction_to_pixel(*dir) : std::nullopt;
                if (!p || channels[i].edge_distance_px(*p) < 0.0) continue;
                float s[4];
                sample_bilinear(*images[i], p->x, p->y, s);
                if (s[3] <= 0.0f) continue;
                for (int c = 0; c < 3; ++c) o[c] += s[c];
                o[3] = 1.0f;
            }
        }
    });
    return out;
}

Image remap_channel_to_fisheye(const DomeConfig& dome, const ChannelFrustum& channel, const Image& image, int size) {
    check_size(size);
    check_image(channel, image, 0);
    const FisheyeMapping fish(dome.fov_deg);
    Image out = blank(size);
    for_rows(size, [&](int y) {
        for (int x = 0; x < size; ++x) {
            const glm::dvec2 uv = FisheyeMapping::pixel_to_uv(glm::dvec2(x + 0.5, y + 0.5), size);
            const auto dir = fish.uv_to_direction(uv);
            if (!dir) continue;
            const auto p = channel.dome_direction_to_pixel(*dir);
            if (!p || channel.edge_distance_px(*p) < 0.0) continue;
            float s[4];
            sample_bilinear(image, p->x, p->y, s);
            float* o = out.pixel(x, y);
            for (int c = 0; c < 3; ++c) o[c] = s[c];
            o[3] = 1.0f;
        }
    });
    return out;
}

namespace {

struct ChannelFiles {
    std::map<uint64_t, std::string> by_frame;  // frame -> path (EXR preferred over PNG)
};

ChannelFiles scan_channel_dir(const fs::path& dir) {
    static const std::regex name_re(R"(frame_(\d+)\.(exr|png))");
    ChannelFiles files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        std::error_code ec2;
        if (!entry.is_regular_file(ec2)) continue;
        const std::string name = entry.path().filename().string();
        std::smatch m;
        if (!std::regex_match(name, m, name_re)) continue;
        uint64_t frame = 0;
        try {
            frame = std::stoull(m[1].str());
        } catch (const std::exception&) {
            continue;
        }
        auto it = files.by_frame.find(frame);
        const bool is_exr = m[2].str() == "exr";
        if (it == files.by_frame.end() || is_exr) files.by_frame[frame] = entry.path().string();
    }
    return files;
}

std::string frame_label(uint64_t frame) { return "frame " + std::to_string(frame); }

// Scans every channel's directory (files[i] for config.channels[i]) and returns the frames to
// stitch: all that any channel has, or only_frame alone; empty (with the problem reported) when
// there is nothing to stitch.
std::set<uint64_t> frames_to_stitch(const ClusterConfig& config, const std::string& in_dir,
                                    std::optional<uint64_t> only_frame, std::vector<ChannelFiles>& files,
                                    StitchReport& report) {
    std::set<uint64_t> all_frames;
    for (const auto& ch : config.channels) {
        const fs::path dir = fs::path(in_dir) / ch.name;
        files.push_back(scan_channel_dir(dir));
        if (files.back().by_frame.empty())
            report.problems.push_back("channel " + ch.name + ": no frames in " + dir.string());
        for (const auto& [f, _] : files.back().by_frame) all_frames.insert(f);
    }
    if (only_frame) {
        if (!all_frames.count(*only_frame)) {
            report.problems.push_back(frame_label(*only_frame) + ": not found in any channel under " + in_dir);
            return {};
        }
        all_frames = {*only_frame};
    }
    if (all_frames.empty())
        report.problems.push_back(in_dir + ": no channel frames (expected " + in_dir +
                                  "/<channel name>/frame_NNNNNN.exr or .png)");
    return all_frames;
}

// The domemaster is always written as PNG, and also as EXR when the channels are.
std::vector<std::string> dome_formats(const ClusterConfig& config) {
    std::vector<std::string> formats = {"png"};
    if (std::find(config.output.formats.begin(), config.output.formats.end(), "exr") != config.output.formats.end())
        formats.push_back("exr");
    return formats;
}

// The readable channel images of one frame, in config order, with what each recorded.
struct FrameChannels {
    std::vector<ChannelFrustum> frusta;
    std::vector<Image> images;
    std::vector<FrameMetadata> metas;
    std::vector<std::string> names;
};

// Reports where a channel image disagrees with the config or its own file name (it is used anyway).
// A stereo channel's frame holds both eyes: the domemaster takes the left (row 0 at the top, so
// the left eye of a top-bottom frame is its first rows). An anaglyph or a single eye is as it is.
Image left_eye_of(const ChannelConfig& ch, Image im) {
    if (stereo_eye_count(ch.stereo) != 2 || ch.stereo == StereoMode::Anaglyph) return im;
    const glm::ivec2 frame = stereo_frame_size(ch.stereo, ch.width, ch.height);
    if (im.width != frame.x || im.height != frame.y) return im;  // check_channel_image says so
    const glm::ivec2 eye = stereo_eye_size(ch.stereo, ch.width, ch.height);
    Image out;
    out.width = eye.x, out.height = eye.y;
    out.rgba.resize(static_cast<size_t>(eye.x) * eye.y * 4);
    for (int y = 0; y < eye.y; ++y) std::copy_n(im.pixel(0, y), static_cast<size_t>(eye.x) * 4, out.pixel(0, y));
    return out;
}

void check_channel_image(const ChannelConfig& ch, uint64_t frame, const std::string& path, const Image& im,
                         const FrameMetadata& meta, const std::string& label, StitchReport& report) {
    const glm::ivec2 size = stereo_frame_size(ch.stereo, ch.width, ch.height);
    if (!ch.calibration && (im.width != size.x || im.height != size.y))
        report.problems.push_back(label + ": " + path + " is " + std::to_string(im.width) + "x" +
                                  std::to_string(im.height) + " but channel " + ch.name + " is " +
                                  std::to_string(size.x) + "x" + std::to_string(size.y) +
                                  " in the config (resampled with its own size)");
    if (meta.frame != frame)
        report.problems.push_back(label + ": " + path + " records frame " + std::to_string(meta.frame));
    if (meta.channel_id != ch.id)
        report.problems.push_back(label + ": " + path + " records channel " + std::to_string(meta.channel_id) +
                                  ", the config says " + ch.name + " is channel " + std::to_string(ch.id));
}

// A calibrated channel's file is its projector frame: back into the channel's render space.
Image channel_space(const ChannelConfig& ch, const std::optional<ProjectorWarp>& warp, Image im) {
    if (!warp) return im;
    return projector_frame_to_channel(*warp, im, ch.width, ch.height);
}

// Reads frame `frame` of every channel; a channel without the frame or with an unreadable file is
// reported and left out. warps[i]: channel i's calibration, if it has one.
FrameChannels read_frame_channels(const ClusterConfig& config, const std::vector<ChannelFiles>& files, uint64_t frame,
                                  const std::vector<std::optional<ProjectorWarp>>& warps, const std::string& label,
                                  StitchReport& report) {
    FrameChannels out;
    for (size_t i = 0; i < config.channels.size(); ++i) {
        const auto& ch = config.channels[i];
        auto it = files[i].by_frame.find(frame);
        if (it == files[i].by_frame.end()) {
            report.problems.push_back(label + ": missing in channel " + ch.name);
            continue;
        }
        FrameMetadata meta;
        Image im;
        try {
            im = read_image_radiance(it->second, &meta);
            check_channel_image(ch, frame, it->second, im, meta, label, report);
            im = channel_space(ch, warps[i], left_eye_of(ch, std::move(im)));
        } catch (const std::exception& e) {
            report.problems.push_back(label + ": channel " + ch.name + ": " + e.what());
            continue;
        }
        out.frusta.emplace_back(ch.orientation, ch.fov, im.width, im.height);
        out.images.push_back(std::move(im));
        out.metas.push_back(std::move(meta));
        out.names.push_back(ch.name);
    }
    return out;
}

// Sync check: every channel must have rendered the same snapshot.
void check_snapshot_hashes(const FrameChannels& channels, const std::string& label, StitchReport& report) {
    const auto& metas = channels.metas;
    bool agree = true;
    for (const auto& m : metas)
        if (m.snapshot_hash.empty() || m.snapshot_hash != metas.front().snapshot_hash) agree = false;
    if (agree) return;
    std::string msg = label + ": snapshot hashes disagree:";
    for (size_t k = 0; k < metas.size(); ++k)
        msg += " " + channels.names[k] + "=" + (metas[k].snapshot_hash.empty() ? "(none)" : metas[k].snapshot_hash);
    report.problems.push_back(msg);
}

// Writes the stitched frame with the first channel's time, snapshot and renderer.
std::vector<std::string> write_dome_frame(const ClusterConfig& config, const std::string& out_dir, uint64_t frame,
                                          const Image& dome, const FrameMetadata& first,
                                          const std::vector<std::string>& formats) {
    FrameMetadata out_meta;
    out_meta.channel_id = -1;
    out_meta.channel_name = "dome";
    out_meta.frame = frame;
    out_meta.sim_time_s = first.sim_time_s;
    out_meta.snapshot_hash = first.snapshot_hash;
    out_meta.renderer = first.renderer;
    out_meta.tone_white = first.tone_white;  // the snapshot's, as the exposure: every channel's
    out_meta.adapted_cd_m2 = first.adapted_cd_m2;
    out_meta.night_vision = first.night_vision;
    out_meta.acuity_blur = first.acuity_blur;
    // The frame's own exposure (the master's auto exposure varies it per frame; all channels
    // share it), else the configured one.
    const double exposure = first.exposure > 0.0 ? first.exposure : config.output.exposure;
    // The eye's acuity at night blurs what the PNG shows; the EXR stays the physical sky.
    const double sigma_rad = out_meta.acuity_sigma_rad();
    const double rad_per_px = glm::radians(config.dome.fov_deg) / dome.width;
    if (!acuity_blur_needed(sigma_rad, rad_per_px)) return write_frame(out_dir, dome, out_meta, formats, exposure);
    std::vector<std::string> written;
    auto write = [&](const Image& image, const std::string& format) {
        for (auto& p : write_frame(out_dir, image, out_meta, {format}, exposure)) written.push_back(std::move(p));
    };
    for (const std::string& f : formats) {
        if (f == "png")
            write(acuity_blurred(dome, DomemasterRays(config.dome.fov_deg, dome.width), sigma_rad), f);
        else
            write(dome, f);
    }
    return written;
}

// Every calibrated channel's projector warp; a projector frame is stitched from its EXR, the light
// the projector sends (linear, after the blend): its PNG is encoded for the projector's gamma.
std::vector<std::optional<ProjectorWarp>> channel_warps(const ClusterConfig& config, std::vector<ChannelFiles>& files,
                                                        StitchReport& report) {
    std::vector<std::optional<ProjectorWarp>> warps;
    for (size_t i = 0; i < config.channels.size(); ++i) {
        const auto& c = config.channels[i].calibration;
        warps.push_back(c ? std::optional(load_channel_warp(*c)) : std::nullopt);
        if (!c) continue;
        for (auto it = files[i].by_frame.begin(); it != files[i].by_frame.end();)
            if (fs::path(it->second).extension() != ".exr") {
                report.problems.push_back(it->second + ": a projector frame is stitched from its EXR (linear light)");
                it = files[i].by_frame.erase(it);
            } else {
                ++it;
            }
    }
    return warps;
}

// Calibrated channels carry their blend in their light: summed. Plain renders: feathered.
Image stitch_frame(const ClusterConfig& config, const FrameChannels& channels, bool calibrated, int size) {
    std::vector<const Image*> ptrs;
    for (const auto& im : channels.images) ptrs.push_back(&im);
    return calibrated ? sum_domemaster(config.dome, channels.frusta, ptrs, size)
                      : stitch_domemaster(config.dome, channels.frusta, ptrs, size);
}

}  // namespace

StitchReport stitch_run_directory(const ClusterConfig& config, const std::string& in_dir, const std::string& out_dir,
                                  std::optional<uint64_t> only_frame, int size) {
    StitchReport report;
    if (size <= 0) size = config.output.domemaster_size;
    check_size(size);
    if (config.channels.empty()) {
        report.problems.push_back(config.file + ": the config has no channels");
        return report;
    }
    if (!fs::is_directory(in_dir)) {
        report.problems.push_back(in_dir + ": not a directory");
        return report;
    }
    std::vector<ChannelFiles> files;
    const std::set<uint64_t> frames = frames_to_stitch(config, in_dir, only_frame, files, report);
    const auto warps = channel_warps(config, files, report);
    const bool calibrated = std::any_of(warps.begin(), warps.end(), [](const auto& w) { return w.has_value(); });
    const std::vector<std::string> formats = dome_formats(config);
    for (uint64_t frame : frames) {
        const std::string label = frame_label(frame);
        const FrameChannels channels = read_frame_channels(config, files, frame, warps, label, report);
        if (channels.images.empty()) {
            report.problems.push_back(label + ": no readable channel image, nothing written");
            continue;
        }
        check_snapshot_hashes(channels, label, report);
        const Image dome = stitch_frame(config, channels, calibrated, size);
        const auto written = write_dome_frame(config, out_dir, frame, dome, channels.metas.front(), formats);
        report.written.insert(report.written.end(), written.begin(), written.end());
        report.frames.push_back(frame);
    }
    return report;
}

}  // namespace cupola
