#include "image/table_file.hpp"

#include <OpenImageIO/imageio.h>
#include <sodium.h>

#include <cmath>
#include <cstdlib>

namespace cupola {

namespace fs = std::filesystem;

bool write_table_file(const fs::path& path, const shading::Texture2DData& t, const std::string& format) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) return false;
    OIIO::ImageSpec spec(t.width, t.height, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    spec.attribute("cupola:format", format);
    const fs::path tmp = path.string() + ".tmp.exr";
    if (!out->open(tmp.string(), spec)) return false;
    // EXR rows run top to bottom; table row 0 is v = 0: write rows reversed so the file shows v up.
    const auto stride = static_cast<OIIO::stride_t>(t.width * sizeof(glm::vec4));
    const auto* last_row = reinterpret_cast<const char*>(t.texels.data()) + stride * (t.height - 1);
    const bool ok = out->write_image(OIIO::TypeDesc::FLOAT, last_row, OIIO::AutoStride, -stride) && out->close();
    if (!ok) return false;
    std::error_code ec;
    fs::rename(tmp, path, ec);  // atomic: concurrent processes never read a half-written table
    return !ec;
}

bool read_table_file(const fs::path& path, int w, int h, const std::string& format, shading::Texture2DData& t,
                     std::string& why) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        why = "cannot open";
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width != w || spec.height != h || spec.nchannels != 4) {
        why = "size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + "x" +
              std::to_string(spec.nchannels) + ", expected " + std::to_string(w) + "x" + std::to_string(h) + "x4";
        return false;
    }
    if (const std::string f = spec.get_string_attribute("cupola:format"); f != format) {
        why = "format \"" + f + "\", expected \"" + format + "\"";
        return false;
    }
    t.width = w;
    t.height = h;
    t.texels.assign(static_cast<size_t>(w) * h, glm::vec4(0.0f));
    const auto stride = static_cast<OIIO::stride_t>(w * sizeof(glm::vec4));
    auto* last_row = reinterpret_cast<char*>(t.texels.data()) + stride * (h - 1);
    if (!in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, last_row, OIIO::AutoStride, -stride)) {
        why = "unreadable pixels: " + in->geterror();
        return false;
    }
    for (const auto& v : t.texels)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || v.x < 0 || v.y < 0 || v.z < 0) {
            why = "non-finite or negative texel";
            return false;
        }
    return true;
}

std::string cache_directory(const std::string& kind) {
    if (const char* d = std::getenv("CUPOLA_CACHE_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "cupola" / kind).string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / ".cache" / "cupola" / kind).string();
    return (fs::path(".cupola-cache") / kind).string();
}

std::string cache_key_hex(const std::string& text) {
    unsigned char h[12];
    crypto_generichash(h, sizeof h, reinterpret_cast<const unsigned char*>(text.data()), text.size(), nullptr, 0);
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned char c : h) {
        out += hex[c >> 4];
        out += hex[c & 15];
    }
    return out;
}

}  // namespace cupola
