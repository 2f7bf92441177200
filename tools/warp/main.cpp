// cupola-warp: runs the projector pass (slave/output/warp_pass) on a saved frame, so that a
// calibration can be checked without projectors.
//   cupola-warp --mpcdi FILE --region ID --in FRAME --out FILE [--pfm-rows bottom-first|top-first]
//               [--v-origin bottom|top] [--coordinates region|buffer] [--warp-direction forward|inverse]
//   cupola-warp --bourke FILE --raster WxH --in FRAME --out FILE
//   common: [--exposure X] [--filter N] [--encode gamma|srgb]
// FRAME: the region's buffer content (2d profile) or its frustum render (3d profile, Bourke), as
// EXR (linear light) or PNG (sRGB, decoded). The output has the calibration's raster size: EXR is
// linear light after alpha and beta, before the encode; PNG is encoded for the projector.
// Exit status: 0 written, 1 a runtime error (a bad calibration or frame file, named with its
// field), 2 bad arguments.
#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "calibration/bourke_mesh.hpp"
#include "calibration/mpcdi_package.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_texture.hpp"
#include "image/frame_image.hpp"
#include "output/warp_pass.hpp"
#include "util/cli_main.hpp"
#include "util/cli_parse.hpp"

using namespace cupola;

namespace {

struct Arguments {
    std::string mpcdi, bourke, region, raster, in, out;
    std::string pfm_rows = "bottom-first", v_origin = "bottom", coordinates = "region", warp_direction = "forward";
    std::string encode = "gamma";
    double exposure = 1.0;
    int filter = 4;
};

void declare(CLI::App& app, Arguments& a) {
    auto* mpcdi = app.add_option("--mpcdi", a.mpcdi, "MPCDI package (.mpcdi)")->check(CLI::ExistingFile);
    auto* bourke = app.add_option("--bourke", a.bourke, "Paul Bourke warp mesh (.data)")->check(CLI::ExistingFile);
    mpcdi->excludes(bourke);
    app.add_option("--region", a.region, "MPCDI region id (default: the package's only region)")->needs(mpcdi);
    app.add_option("--raster", a.raster, "projector raster WxH (a Bourke mesh has none)")->needs(bourke);
    app.add_option("--in", a.in, "frame: EXR (linear) or PNG (sRGB)")->required()->check(CLI::ExistingFile);
    app.add_option("--out", a.out, "projector raster: .exr (linear, before the encode) or .png (encoded)")->required();
    app.add_option("--exposure", a.exposure, "multiplies the frame's linear values")->check(CLI::Range(0.0, 1e9));
    app.add_option("--filter", a.filter, "footprint filter: most taps per axis, 1 = off")->check(CLI::Range(1, 8));
    app.add_option("--encode", a.encode, "PNG encode: gamma (the projector's) or srgb")
        ->check(CLI::IsMember({"gamma", "srgb"}));
    app.add_option("--pfm-rows", a.pfm_rows, "MPCDI warp PFM row order")
        ->check(CLI::IsMember({"bottom-first", "top-first"}));
    app.add_option("--v-origin", a.v_origin, "MPCDI v = 0 at the content's bottom or top")
        ->check(CLI::IsMember({"bottom", "top"}));
    app.add_option("--coordinates", a.coordinates, "MPCDI (u, v) local to the region or global to the buffer")
        ->check(CLI::IsMember({"region", "buffer"}));
    app.add_option("--warp-direction", a.warp_direction, "MPCDI warp: projector -> content, or inverse")
        ->check(CLI::IsMember({"forward", "inverse"}));
}

// "1920x1200" -> (1920, 1200); throws std::invalid_argument naming the flag.
std::pair<int, int> parse_raster(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 || h <= 0 ||
        w > 16384 || h > 16384)
        throw std::invalid_argument("--raster '" + text + "' is not WxH (positive, at most 16384)");
    return {w, h};
}

std::string only_region(const MpcdiPackage& package) {
    if (package.regions().size() != 1) {
        std::string ids;
        for (const auto& r : package.regions()) ids += (ids.empty() ? "" : ", ") + r.id;
        throw std::invalid_argument(package.name() + " has " + std::to_string(package.regions().size()) + " regions (" +
                                    ids + "): name one with --region");
    }
    return package.regions().front().id;
}

ProjectorWarp load_warp(const Arguments& a) {
    if (!a.bourke.empty()) {
        if (a.raster.empty()) throw std::invalid_argument("--bourke needs --raster WxH");
        const auto [w, h] = parse_raster(a.raster);
        return read_bourke_mesh(a.bourke, w, h);
    }
    if (a.mpcdi.empty()) throw std::invalid_argument("give a calibration: --mpcdi FILE or --bourke FILE");
    MpcdiReading reading;
    reading.set("pfm_rows", a.pfm_rows);
    reading.set("v_origin", a.v_origin);
    reading.set("coordinates", a.coordinates);
    reading.set("warp_direction", a.warp_direction);
    const MpcdiPackage package = MpcdiPackage::open(a.mpcdi);
    return package.read_region(a.region.empty() ? only_region(package) : a.region, reading);
}

// The frame's linear values as displayed: EXR as stored, PNG decoded from sRGB (read_image divides
// a PNG by the exposure it records; that is multiplied back).
Image load_frame(const std::string& path) {
    FrameMetadata meta;
    Image img = read_image(path, &meta);
    const std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
    if (ext == ".png" || ext == ".PNG")
        for (size_t i = 0; i < img.rgba.size(); ++i)
            if (i % 4 != 3) img.rgba[i] *= static_cast<float>(meta.exposure);
    return img;
}

// The frame as a texture, v up: texture row 0 is the image's bottom row.
GlTexture upload_frame(const Image& img) {
    std::vector<glm::vec4> texels(static_cast<size_t>(img.width) * img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* p = img.pixel(x, img.height - 1 - y);
            texels[static_cast<size_t>(y) * img.width + x] = glm::vec4(p[0], p[1], p[2], 1.0f);
        }
    return GlTexture(img.width, img.height, texels.data(), GL_NEAREST);
}

void write_raster(const std::string& path, int w, int h, OIIO::TypeDesc type, const void* data) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error("cannot write " + path + ": " + OIIO::geterror());
    OIIO::ImageSpec spec(w, h, 4, type);
    spec.alpha_channel = 3;
    if (!out->open(path, spec) || !out->write_image(type, data) || !out->close())
        throw std::runtime_error("cannot write " + path + ": " + out->geterror());
}

int run(const Arguments& a) {
    const bool exr = a.out.size() >= 4 && a.out.substr(a.out.size() - 4) == ".exr";
    const bool png = a.out.size() >= 4 && a.out.substr(a.out.size() - 4) == ".png";
    if (!exr && !png) throw std::invalid_argument("--out '" + a.out + "' must end in .exr or .png");
    ProjectorWarp warp = load_warp(a);
    const Image frame = load_frame(a.in);
    EglContext gl(-1);
    const GlTexture content = upload_frame(frame);
    const WarpOptions options{a.encode == "srgb" ? WarpOptions::Encode::Srgb : WarpOptions::Encode::Gamma, a.filter};
    WarpPass pass(std::move(warp), frame.width, frame.height, options);
    pass.draw(content.id(), a.exposure);
    if (exr) {
        const Image lin = pass.read_linear();
        write_raster(a.out, lin.width, lin.height, OIIO::TypeDesc::FLOAT, lin.rgba.data());
    } else {
        const std::vector<uint8_t> enc = pass.read_encoded();
        write_raster(a.out, pass.width(), pass.height(), OIIO::TypeDesc::UINT8, enc.data());
    }
    std::printf("wrote %s (%dx%d)\n", a.out.c_str(), pass.width(), pass.height());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"cupola-warp: a saved frame through a projector calibration (MPCDI region or Bourke mesh)"};
    Arguments args;
    declare(app, args);
    if (const auto stop = parse_command_line(app, argc, argv, "cupola-warp")) return *stop;
    setup_logging("cupola-warp", false, true);
    return run_main("cupola-warp", [&] { return run(args); });
}
