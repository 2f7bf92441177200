#pragma once
// MPCDI alpha and beta maps as PNG files (VESA MPCDI v2.0 (2015)): 8 or 16 bits, 1 or 3
// components, any size. Read into the linear BlendMap of projector_warp.hpp: stored values are
// normalized (÷255 or ÷65535), three components are averaged, and the result is raised to
// gamma_embedded (§2.5.1.2.4: Linear = (Encoded / Scale)^gamma; 1 for beta, which is linear).
#include <string>

#include "calibration/projector_warp.hpp"

namespace cupola {

struct BlendMapEncoding {
    int bit_depth = 8;   // 8 | 16 (0 when reading: whatever the PNG holds)
    int components = 1;  // 1 | 3 (0 when reading: whatever the PNG holds)
    double gamma_embedded = 1.0;
};

// `name` ("FILE region R alphaMap PATH") is named in every CalibrationError. The PNG's own bit
// depth and channel count must match `expected` (what mpcdi.xml says).
BlendMap decode_blend_map(const std::string& png_bytes, const std::string& name, const BlendMapEncoding& expected);

// The PNG bytes of a map: value^(1/gamma_embedded), quantized, in every component.
std::string encode_blend_map(const BlendMap& map, const std::string& name, const BlendMapEncoding& encoding);

}  // namespace cupola
