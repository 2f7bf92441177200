#include "calibration/blend_map_file.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "calibration/calibration_error.hpp"

namespace cupola {

namespace {

void check_encoding(const BlendMapEncoding& e, const std::string& name, bool reading) {
    if (e.bit_depth != 8 && e.bit_depth != 16 && !(reading && e.bit_depth == 0))
        throw CalibrationError(name, "bitDepth", std::to_string(e.bit_depth) + " is not 8 or 16");
    if (e.components != 1 && e.components != 3 && !(reading && e.components == 0))
        throw CalibrationError(name, "componentDepth", std::to_string(e.components) + " is not 1 or 3");
    if (!(e.gamma_embedded > 0.0) || !std::isfinite(e.gamma_embedded))
        throw CalibrationError(name, "gammaEmbedded", "must be a positive number");
}

void check_spec(const OIIO::ImageSpec& spec, const std::string& name, const BlendMapEncoding& expected) {
    const int bits = spec.format == OIIO::TypeDesc::UINT16 ? 16 : spec.format == OIIO::TypeDesc::UINT8 ? 8 : 0;
    if (bits == 0 || (expected.bit_depth != 0 && bits != expected.bit_depth))
        throw CalibrationError(name, "bitDepth",
                               "mpcdi.xml says " + std::to_string(expected.bit_depth) + " bits, the PNG holds " +
                                   std::string(spec.format.c_str()));
    if ((spec.nchannels != 1 && spec.nchannels != 3) ||
        (expected.components != 0 && spec.nchannels != expected.components))
        throw CalibrationError(name, "componentDepth",
                               "mpcdi.xml says " + std::to_string(expected.components) + " components, the PNG has " +
                                   std::to_string(spec.nchannels));
    if (spec.width < 1 || spec.height < 1 || static_cast<int64_t>(spec.width) * spec.height > (int64_t(1) << 25))
        throw CalibrationError(name, "size", "PNG size out of range");
}

}  // namespace

BlendMap decode_blend_map(const std::string& png_bytes, const std::string& name, const BlendMapEncoding& expected) {
    check_encoding(expected, name, true);
    if (!(expected.gamma_embedded > 0.0) || !std::isfinite(expected.gamma_embedded))
        throw CalibrationError(name, "gammaEmbedded", "must be a positive number");
    OIIO::Filesystem::IOMemReader reader(png_bytes.data(), png_bytes.size());
    auto in = OIIO::ImageInput::create("map.png", false, nullptr, &reader);
    if (!in) throw CalibrationError(name, "PNG", "no PNG reader: " + OIIO::geterror());
    OIIO::ImageSpec spec;
    OIIO::ImageSpec config;
    void* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!in->open("map.png", spec, config))
        throw CalibrationError(name, "PNG", "not a readable PNG: " + in->geterror());
    check_spec(spec, name, expected);
    const size_t pixels = static_cast<size_t>(spec.width) * spec.height;
    std::vector<float> raw(pixels * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, raw.data()))
        throw CalibrationError(name, "PNG", "cannot decode: " + in->geterror());
    BlendMap map{spec.width, spec.height, std::vector<float>(pixels)};
    for (size_t p = 0; p < pixels; ++p) {
        double sum = 0.0;
        for (int c = 0; c < spec.nchannels; ++c) sum += raw[p * spec.nchannels + c];
        map.value[p] = static_cast<float>(std::pow(sum / spec.nchannels, expected.gamma_embedded));
    }
    return map;
}

std::string encode_blend_map(const BlendMap& map, const std::string& name, const BlendMapEncoding& encoding) {
    check_encoding(encoding, name, false);
    if (map.width < 1 || map.height < 1 || map.value.size() != static_cast<size_t>(map.width) * map.height)
        throw CalibrationError(name, "size", "inconsistent blend map to encode");
    const size_t pixels = map.value.size();
    std::vector<float> raw(pixels * encoding.components);
    for (size_t p = 0; p < pixels; ++p) {
        const double v = std::clamp(static_cast<double>(map.value[p]), 0.0, 1.0);
        const float stored = static_cast<float>(std::pow(v, 1.0 / encoding.gamma_embedded));
        for (int c = 0; c < encoding.components; ++c) raw[p * encoding.components + c] = stored;
    }
    std::vector<unsigned char> out_bytes;
    OIIO::Filesystem::IOVecOutput writer(out_bytes);
    auto out = OIIO::ImageOutput::create("map.png", &writer);
    if (!out) throw CalibrationError(name, "PNG", "no PNG writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(map.width, map.height, encoding.components,
                         encoding.bit_depth == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8);
    if (!out->open("map.png", spec) || !out->write_image(OIIO::TypeDesc::FLOAT, raw.data()) || !out->close())
        throw CalibrationError(name, "PNG", "cannot encode: " + out->geterror());
    return std::string(out_bytes.begin(), out_bytes.end());
}

}  // namespace cupola
