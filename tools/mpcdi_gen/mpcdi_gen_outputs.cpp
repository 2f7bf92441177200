#include "mpcdi_gen_outputs.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "calibration/projector_frame_reference.hpp"
#include "calibration/projector_stitch.hpp"

namespace cupola {

namespace {
namespace fs = std::filesystem;

void write_png(const std::string& path, int width, int height, int channels, const std::vector<float>& values) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": cannot create a PNG writer");
    std::vector<unsigned char> bytes(values.size());
    for (size_t k = 0; k < values.size(); ++k)
        bytes[k] = static_cast<unsigned char>(std::lround(std::clamp(values[k], 0.0f, 1.0f) * 255.0f));
    const OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) || !out->close())
        throw std::runtime_error(path + ": " + out->geterror());
}

std::vector<float> rgb_of(const Image& img, double encode_gamma) {
    std::vector<float> v(static_cast<size_t>(img.width) * img.height * 3);
    for (size_t p = 0; p < static_cast<size_t>(img.width) * img.height; ++p)
        for (int c = 0; c < 3; ++c)
            v[p * 3 + c] = static_cast<float>(std::pow(std::max(img.rgba[p * 4 + c], 0.0f), 1.0 / encode_gamma));
    return v;
}

// Azimuth/elevation lines every 10 degrees (white) on a tint per channel (linear light).
Image pattern_render(const CalibratedFrustum& f, int size, const glm::vec3& tint) {
    const ChannelFrustum frustum(f.orientation, f.fov, size, size);
    Image img;
    img.width = img.height = size;
    img.rgba.assign(static_cast<size_t>(size) * size * 4, 1.0f);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::dvec3 d = frustum.pixel_to_dome_direction({x + 0.5, y + 0.5});
            const double el = glm::degrees(std::asin(std::clamp(d.y, -1.0, 1.0)));
            const double az = glm::degrees(std::atan2(d.x, -d.z));
            auto near_line = [](double a, double width) {
                return std::abs(a / 10.0 - std::round(a / 10.0)) * 10.0 < width;
            };
            const bool line =
                near_line(el, 0.35) || (el < 80.0 && near_line(az, 0.35 / std::max(std::cos(glm::radians(el)), 0.1)));
            const glm::vec3 c = line ? glm::vec3(1.0f) : tint;
            float* p = img.pixel(x, y);
            p[0] = c.r, p[1] = c.g, p[2] = c.b;
        }
    return img;
}

// A frame's stored values as they are (no sRGB decode): what the projector receives.
Image read_raw_frame(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error(path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> v(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, v.data()))
        throw std::runtime_error(path + ": " + in->geterror());
    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.rgba.assign(static_cast<size_t>(spec.width) * spec.height * 4, 1.0f);
    for (size_t p = 0; p < static_cast<size_t>(spec.width) * spec.height; ++p)
        for (int c = 0; c < 3; ++c) img.rgba[p * 4 + c] = v[p * spec.nchannels + std::min(c, spec.nchannels - 1)];
    return img;
}

std::string alpha_mosaic(const std::string& dir, const std::vector<ProjectorWarp>& warps) {
    const int w = warps[0].alpha.width, h = warps[0].alpha.height;
    const int cols = 2, rows = static_cast<int>((warps.size() + 1) / 2);
    std::vector<float> v(static_cast<size_t>(cols * w) * rows * h, 0.0f);
    for (size_t k = 0; k < warps.size(); ++k) {
        const BlendMap& a = warps[k].alpha;
        if (a.width != w || a.height != h) throw std::invalid_argument("alpha maps of different sizes");
        const int ox = static_cast<int>(k % 2) * w, oy = static_cast<int>(k / 2) * h;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                v[static_cast<size_t>(oy + y) * cols * w + ox + x] =
                    std::pow(a.value[static_cast<size_t>(y) * w + x], 1.0f / 2.2f);
    }
    const std::string path = dir + "/dome-4proj-alpha.png";
    write_png(path, cols * w, rows * h, 1, v);
    return path;
}
}  // namespace

void write_calibrated_config(const std::string& template_file, const std::string& out_file,
                             const std::string& mpcdi_file, const std::vector<ProjectorWarp>& warps) {
    std::ifstream in(template_file);
    nlohmann::ordered_json config = nlohmann::ordered_json::parse(in);
    const fs::path out_dir = fs::absolute(out_file).parent_path();
    const std::string relative = fs::relative(fs::absolute(mpcdi_file), out_dir).generic_string();
    nlohmann::ordered_json channels = nlohmann::ordered_json::array();
    for (size_t k = 0; k < warps.size(); ++k)
        channels.push_back({{"id", k},
                            {"name", warps[k].region_id},
                            {"calibration", {{"mpcdi", relative}, {"region", warps[k].region_id}}}});
    config["channels"] = channels;
    std::ofstream(out_file) << config.dump(2) << "\n";
}

std::vector<std::string> write_calibration_images(const std::string& dir, const std::vector<IdealProjector>& projectors,
                                                  const std::vector<ProjectorWarp>& warps) {
    fs::create_directories(dir);
    std::vector<std::string> written{alpha_mosaic(dir, warps)};
    const glm::vec3 tints[] = {{0.35f, 0.05f, 0.05f}, {0.05f, 0.3f, 0.05f}, {0.05f, 0.08f, 0.4f}, {0.3f, 0.25f, 0.02f}};
    std::vector<Image> frames;
    std::vector<double> gammas;
    for (size_t k = 0; k < warps.size(); ++k) {
        const Image render = pattern_render(*warps[k].frustum, 512, tints[k % 4]);
        frames.push_back(reference_projector_frame(warps[k], render, {}));
        gammas.push_back(warps[k].projector_gamma);
    }
    written.push_back(dir + "/dome-4proj-frame.png");
    write_png(written.back(), frames[0].width, frames[0].height, 3, rgb_of(frames[0], 1.0));
    const Image dome = stitch_projector_frames(projectors, frames, gammas, 512);
    written.push_back(dir + "/dome-4proj-stitched.png");
    write_png(written.back(), dome.width, dome.height, 3, rgb_of(dome, 2.2));
    return written;
}

void write_stitched_frames(const std::string& out_file, const std::vector<IdealProjector>& projectors,
                           const std::vector<std::string>& frame_files, const std::vector<double>& gammas, int size) {
    if (frame_files.size() != projectors.size())
        throw std::invalid_argument("--stitch-frames: " + std::to_string(frame_files.size()) + " frames for " +
                                    std::to_string(projectors.size()) + " projectors");
    std::vector<Image> frames;
    for (size_t k = 0; k < frame_files.size(); ++k) {
        frames.push_back(read_raw_frame(frame_files[k]));
        if (frames.back().width != projectors[k].width() || frames.back().height != projectors[k].height())
            throw std::invalid_argument(frame_files[k] + ": not the projector's " +
                                        std::to_string(projectors[k].width()) + "x" +
                                        std::to_string(projectors[k].height()) + " raster");
    }
    const Image dome = stitch_projector_frames(projectors, frames, gammas, size);
    write_png(out_file, dome.width, dome.height, 3, rgb_of(dome, 2.2));
}

}  // namespace cupola
