#include "image/frame_image.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include "shading/shared_shading.hpp"

namespace cupola {

namespace fs = std::filesystem;

namespace {

// Attribute names (see the header comment).
constexpr const char* kAttrChannel = "cupola:channel";
constexpr const char* kAttrChannelName = "cupola:channel_name";
constexpr const char* kAttrFrame = "cupola:frame";
constexpr const char* kAttrSimTime = "cupola:sim_time";
constexpr const char* kAttrHash = "cupola:snapshot_hash";
constexpr const char* kAttrRenderer = "cupola:renderer";
constexpr const char* kAttrExposure = "cupola:exposure";
constexpr const char* kAttrToneWhite = "cupola:tone_white";
constexpr const char* kAttrNightVision = "cupola:night_vision";
constexpr const char* kAttrAcuityBlur = "cupola:acuity_blur";
constexpr const char* kAttrAdapted = "cupola:adapted_cd_m2";

std::string fmt_double(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// NaN -> 0 and +-inf -> +-FLT_MAX: a frame file never holds a non-finite value.
float finite_or_clamped(float v) {
    if (std::isnan(v)) return 0.0f;
    return std::clamp(v, -std::numeric_limits<float>::max(), std::numeric_limits<float>::max());
}

float clamp01(float v) {
    if (std::isnan(v)) return 0.0f;
    return std::clamp(v, 0.0f, 1.0f);
}

std::string oiio_error(const OIIO::ImageOutput* out) {
    std::string msg = out ? out->geterror() : std::string();
    if (msg.empty()) msg = OIIO::geterror();
    if (msg.empty()) msg = "unknown OpenImageIO error";
    return msg;
}

std::string oiio_error(const OIIO::ImageInput* in) {
    std::string msg = in ? in->geterror() : std::string();
    if (msg.empty()) msg = OIIO::geterror();
    if (msg.empty()) msg = "unknown OpenImageIO error";
    return msg;
}

// A unique hidden name next to the final file, with the same extension so that any tool
// recognises the format; the reader-visible name appears only on the final rename.
std::string temp_path_for(const fs::path& final_path) {
    static std::atomic<unsigned> counter{0};
    const std::string name = "." + final_path.stem().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter.fetch_add(1)) + final_path.extension().string();
    return (final_path.parent_path() / name).string();
}

void put_metadata(OIIO::ImageSpec& spec, const FrameMetadata& meta, double exposure, bool strings_only) {
    // PNG can only keep text chunks, so PNG files carry every attribute as a string; EXR keeps
    // the typed attributes. read_image() accepts either form.
    if (strings_only) {
        spec.attribute(kAttrChannel, std::to_string(meta.channel_id));
        spec.attribute(kAttrFrame, std::to_string(meta.frame));
        spec.attribute(kAttrExposure, fmt_double(exposure));
        spec.attribute(kAttrToneWhite, fmt_double(meta.tone_white));
        spec.attribute(kAttrAdapted, fmt_double(meta.adapted_cd_m2));
        spec.attribute(kAttrNightVision, meta.night_vision ? "1" : "0");
        spec.attribute(kAttrAcuityBlur, meta.acuity_blur ? "1" : "0");
    } else {
        spec.attribute(kAttrChannel, meta.channel_id);
        if (meta.frame <= static_cast<uint64_t>(std::numeric_limits<int>::max()))
            spec.attribute(kAttrFrame, static_cast<int>(meta.frame));
        else
            spec.attribute(kAttrFrame, std::to_string(meta.frame));
        spec.attribute(kAttrExposure, static_cast<float>(exposure));
        spec.attribute(kAttrToneWhite, static_cast<float>(meta.tone_white));
        spec.attribute(kAttrAdapted, static_cast<float>(meta.adapted_cd_m2));
        spec.attribute(kAttrNightVision, meta.night_vision ? 1 : 0);
        spec.attribute(kAttrAcuityBlur, meta.acuity_blur ? 1 : 0);
    }
    spec.attribute(kAttrChannelName, meta.channel_name);
    spec.attribute(kAttrSimTime, fmt_double(meta.sim_time_s));
    spec.attribute(kAttrHash, meta.snapshot_hash);
    spec.attribute(kAttrRenderer, meta.renderer);
    spec.attribute("Software", "Cupola");
}

void write_pixels(const fs::path& final_path, const std::string& format, const OIIO::ImageSpec& spec,
                  OIIO::TypeDesc data_type, const void* data);

void write_one(const fs::path& final_path, const std::string& format, const Image& image, const FrameMetadata& meta,
               double exposure) {
    const size_t n = static_cast<size_t>(image.width) * image.height * 4;
    const float ex = static_cast<float>(exposure);

    OIIO::ImageSpec spec;
    std::vector<float> fdata;
    std::vector<unsigned char> bdata;
    const void* data = nullptr;
    OIIO::TypeDesc data_type;
    if (format == "exr") {
        // 32-bit float: physical scene units span ~1e-6 (night sky) to ~2e9 (the Sun's disc), which
        // half floats (max 65504) cannot hold even after exposure.
        spec = OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
        spec.attribute("oiio:ColorSpace", "Linear");
        fdata.resize(n);
        for (size_t i = 0; i < n; i += 4) {
            for (int c = 0; c < 3; ++c) fdata[i + c] = finite_or_clamped(image.rgba[i + c] * ex);
            fdata[i + 3] = finite_or_clamped(image.rgba[i + 3]);
        }
        data = fdata.data();
        data_type = OIIO::TypeDesc::FLOAT;
        put_metadata(spec, meta, exposure, false);
    } else {  // png
        spec = OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        // Pixel values pass through unchanged: no (de)association of alpha by OIIO.
        spec.attribute("oiio:UnassociatedAlpha", 1);
        bdata.resize(n);
        for (size_t i = 0; i < n; i += 4) {
            const glm::vec3 shown = display_color(glm::vec3(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]) * ex,
                                                  meta.tone_white, exposure, meta.night_adapted_cd_m2());
            for (int c = 0; c < 3; ++c)
                bdata[i + c] = static_cast<unsigned char>(std::lround(linear_to_srgb(shown[c]) * 255.0f));
            bdata[i + 3] = static_cast<unsigned char>(std::lround(clamp01(image.rgba[i + 3]) * 255.0f));
        }
        data = bdata.data();
        data_type = OIIO::TypeDesc::UINT8;
        put_metadata(spec, meta, exposure, true);
    }
    spec.alpha_channel = 3;
    write_pixels(final_path, format, spec, data_type, data);
}

// Writes one image through a hidden temporary file, renamed to final_path once complete.
void write_pixels(const fs::path& final_path, const std::string& format, const OIIO::ImageSpec& spec,
                  OIIO::TypeDesc data_type, const void* data) {
    const std::string path = final_path.string();
    const std::string tmp = temp_path_for(final_path);
    auto out = OIIO::ImageOutput::create(format);
    if (!out) throw std::runtime_error("cannot write " + path + ": " + oiio_error(out.get()));
    if (!out->open(tmp, spec)) {
        const std::string msg = oiio_error(out.get());
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error("cannot write " + path + ": " + msg);
    }
    bool ok = out->write_image(data_type, data);
    std::string msg = ok ? std::string() : oiio_error(out.get());
    if (!out->close() && ok) {
        ok = false;
        msg = oiio_error(out.get());
    }
    if (!ok) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error("cannot write " + path + ": " + msg);
    }
    std::error_code ec;
    fs::rename(tmp, final_path, ec);
    if (ec) {
        std::error_code ec2;
        fs::remove(tmp, ec2);
        throw std::runtime_error("cannot write " + path + ": rename failed: " + ec.message());
    }
}

// Attribute as string whatever its stored type; empty when absent.
bool get_string_attr(const OIIO::ImageSpec& spec, const char* name, std::string& out) {
    const OIIO::ParamValue* p = spec.find_attribute(name);
    if (!p) return false;
    out = p->get_string();
    return true;
}

bool get_int64_attr(const OIIO::ImageSpec& spec, const char* name, long long& out) {
    const OIIO::ParamValue* p = spec.find_attribute(name);
    if (!p) return false;
    if (p->type() == OIIO::TypeDesc::INT || p->type() == OIIO::TypeDesc::UINT) {
        out = p->get_int();
        return true;
    }
    if (p->type() == OIIO::TypeDesc::STRING) {
        const std::string s = p->get_string();
        char* end = nullptr;
        errno = 0;
        const long long v = std::strtoll(s.c_str(), &end, 10);
        if (end == s.c_str() || *end != '\0' || errno != 0) return false;
        out = v;
        return true;
    }
    return false;
}

bool get_double_attr(const OIIO::ImageSpec& spec, const char* name, double& out) {
    const OIIO::ParamValue* p = spec.find_attribute(name);
    if (!p) return false;
    if (p->type() == OIIO::TypeDesc::FLOAT) {
        out = p->get_float();
        return true;
    }
    if (p->type() == OIIO::TypeDesc::DOUBLE) {
        out = *static_cast<const double*>(p->data());
        return true;
    }
    if (p->type() == OIIO::TypeDesc::INT) {
        out = p->get_int();
        return true;
    }
    if (p->type() == OIIO::TypeDesc::STRING) {
        const std::string s = p->get_string();
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (end == s.c_str() || *end != '\0') return false;
        out = v;
        return true;
    }
    return false;
}

Image read_impl(const std::string& path, FrameMetadata* meta, bool undo_exposure_always) {
    // Pixel values come back exactly as stored: OIIO must not premultiply PNG colour by alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) throw std::runtime_error("cannot read " + path + ": " + oiio_error(in.get()));
    const OIIO::ImageSpec spec = in->spec();
    const int w = spec.width, h = spec.height, nc = spec.nchannels;
    if (w <= 0 || h <= 0 || nc <= 0) throw std::runtime_error("cannot read " + path + ": empty image");
    std::vector<float> buf(static_cast<size_t>(w) * h * nc);
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, buf.data())) {
        const std::string msg = oiio_error(in.get());
        throw std::runtime_error("cannot read " + path + ": " + msg);
    }
    in->close();

    // Display-referred (8/16-bit integer) files are sRGB-encoded; float/half files are linear.
    const bool display_referred =
        !(spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
          spec.format.basetype == OIIO::TypeDesc::DOUBLE);
    double exposure = 1.0;
    double recorded = 1.0;
    if (get_double_attr(spec, kAttrExposure, recorded) && std::isfinite(recorded) && recorded > 0.0)
        exposure = recorded;
    const bool undo = display_referred || undo_exposure_always;
    const float inv_exposure = undo ? static_cast<float>(1.0 / exposure) : 1.0f;
    double tone_white = 0.0;  // a display file's curve is undone before the exposure
    if (!get_double_attr(spec, kAttrToneWhite, tone_white) || !(tone_white > 0.0)) tone_white = 0.0;

    Image img;
    img.width = w;
    img.height = h;
    img.rgba.assign(static_cast<size_t>(w) * h * 4, 0.0f);
    const int alpha =
        spec.alpha_channel >= 0 && spec.alpha_channel < nc ? spec.alpha_channel : (nc == 2 ? 1 : (nc >= 4 ? 3 : -1));
    for (size_t i = 0, npx = static_cast<size_t>(w) * h; i < npx; ++i) {
        const float* s = &buf[i * nc];
        float rgb[3];
        if (nc < 3) {
            rgb[0] = rgb[1] = rgb[2] = s[0];
        } else {
            rgb[0] = s[0];
            rgb[1] = s[1];
            rgb[2] = s[2];
        }
        float* d = &img.rgba[i * 4];
        glm::vec3 lin(rgb[0], rgb[1], rgb[2]);
        if (display_referred)
            lin = shading::tone_curve_inverse(
                glm::vec3(srgb_to_linear(rgb[0]), srgb_to_linear(rgb[1]), srgb_to_linear(rgb[2])),
                static_cast<float>(tone_white));
        for (int c = 0; c < 3; ++c) d[c] = lin[c] * inv_exposure;
        d[3] = alpha >= 0 ? s[alpha] : 1.0f;
    }

    if (meta) {
        FrameMetadata m;
        long long iv = 0;
        if (get_int64_attr(spec, kAttrChannel, iv)) m.channel_id = static_cast<int>(iv);
        get_string_attr(spec, kAttrChannelName, m.channel_name);
        std::string fs_;
        if (get_string_attr(spec, kAttrFrame, fs_)) {
            char* end = nullptr;
            const unsigned long long v = std::strtoull(fs_.c_str(), &end, 10);
            if (end != fs_.c_str() && *end == '\0') m.frame = v;
        }
        get_double_attr(spec, kAttrSimTime, m.sim_time_s);
        get_string_attr(spec, kAttrHash, m.snapshot_hash);
        get_string_attr(spec, kAttrRenderer, m.renderer);
        m.exposure = exposure;
        m.tone_white = tone_white;
        get_double_attr(spec, kAttrAdapted, m.adapted_cd_m2);
        long long night = 0;
        m.night_vision = get_int64_attr(spec, kAttrNightVision, night) && night == 1;
        long long blur = 0;
        m.acuity_blur = get_int64_attr(spec, kAttrAcuityBlur, blur) && blur == 1;
        *meta = std::move(m);
    }
    return img;
}

}  // namespace

std::string frame_file_name(uint64_t frame, const std::string& extension) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "frame_%06llu", static_cast<unsigned long long>(frame));
    std::string ext = extension;
    if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
    return std::string(buf) + (ext.empty() ? "" : "." + ext);
}

std::vector<std::string> write_frame(const std::string& dir, const Image& image, const FrameMetadata& meta,
                                     const std::vector<std::string>& formats, double exposure) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
        throw std::runtime_error("cannot write frame " + std::to_string(meta.frame) + " to " + dir + ": image is " +
                                 std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                                 std::to_string(image.rgba.size()) + " floats");
    if (!std::isfinite(exposure) || exposure <= 0.0)
        throw std::runtime_error("cannot write frame to " + dir + ": exposure " + fmt_double(exposure) +
                                 " is not a positive number");
    for (const auto& f : formats)
        if (f != "png" && f != "exr")
            throw std::runtime_error("cannot write frame to " + dir + ": unknown image format \"" + f +
                                     "\" (expected png or exr)");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw std::runtime_error("cannot create directory " + dir + ": " +
                                 (ec ? ec.message() : std::string("not a directory")));
    std::vector<std::string> written;
    for (const auto& f : formats) {
        const fs::path p = fs::path(dir) / frame_file_name(meta.frame, f);
        write_one(p, f, image, meta, exposure);
        written.push_back(p.string());
    }
    return written;
}

std::string write_encoded_png(const std::string& dir, const EncodedImage& image, const FrameMetadata& meta,
                              double exposure) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
        throw std::runtime_error("cannot write frame " + std::to_string(meta.frame) + " to " + dir +
                                 ": encoded image is " + std::to_string(image.width) + "x" +
                                 std::to_string(image.height) + " with " + std::to_string(image.rgba.size()) +
                                 " bytes");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw std::runtime_error("cannot create directory " + dir + ": " +
                                 (ec ? ec.message() : std::string("not a directory")));
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.alpha_channel = 3;
    put_metadata(spec, meta, exposure, true);
    const fs::path p = fs::path(dir) / frame_file_name(meta.frame, "png");
    write_pixels(p, "png", spec, OIIO::TypeDesc::UINT8, image.rgba.data());
    return p.string();
}

Image read_image(const std::string& path, FrameMetadata* meta) { return read_impl(path, meta, false); }

Image read_image_radiance(const std::string& path, FrameMetadata* meta) { return read_impl(path, meta, true); }

namespace {
// A NaN component counts as 0 (as in the EXR).
glm::vec3 nan_as_zero(const glm::vec3& c) {
    return {std::isnan(c.x) ? 0.0f : c.x, std::isnan(c.y) ? 0.0f : c.y, std::isnan(c.z) ? 0.0f : c.z};
}
}  // namespace

double FrameMetadata::acuity_sigma_rad() const {
    return acuity_blur ? shading::acuity_blur_sigma_rad(static_cast<float>(night_adapted_cd_m2())) : 0.0;
}

glm::vec3 display_color(const glm::vec3& linear, double tone_white) {
    return shading::gamut_map_to_unit_cube(shading::tone_curve(nan_as_zero(linear), static_cast<float>(tone_white)));
}

glm::vec3 display_color(const glm::vec3& linear, double tone_white, double exposure, double night_adapted_cd_m2) {
    return display_color(shading::night_vision(nan_as_zero(linear), static_cast<float>(exposure),
                                               static_cast<float>(night_adapted_cd_m2)),
                         tone_white);
}

float linear_to_srgb(float linear) {
    const float x = clamp01(linear);
    if (x <= 0.0031308f) return 12.92f * x;
    return 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float encoded) {
    const float x = clamp01(encoded);
    if (x <= 0.04045f) return x / 12.92f;
    return std::pow((x + 0.055f) / 1.055f, 2.4f);
}

}  // namespace cupola
