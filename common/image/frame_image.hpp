#pragma once
// Channel frames and domemasters on disk, written and read with OpenImageIO.
//  - EXR: 32-bit float RGBA, linear scene radiance times exposure (no tone mapping).
//  - PNG: 8-bit sRGB RGBA after the display transform: exposure, the tone curve (when the frame
//    has a display white), the gamut map into [0, 1]^3
//    (display_color: constant luminance and dominant wavelength, never a per-channel clip of a
//    negative value), sRGB encode. docs/COLOR.md: the primaries (ITU-R BT.709, D65) and units.
// Every file carries metadata attributes so that sync can be checked from the files alone:
//   cupola:channel (int), cupola:channel_name, cupola:frame (int, as string if > 2^31),
//   cupola:sim_time (string, %.17g seconds since J2000), cupola:snapshot_hash (16 hex digits),
//   cupola:renderer (GL_RENDERER string).
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace cupola {

// Linear RGBA float image; row 0 is the TOP row.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;  // width*height*4

    float* pixel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
    const float* pixel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

// 8-bit RGBA already encoded for a display (what a projector is sent); row 0 is the TOP row.
struct EncodedImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // width*height*4
};

struct FrameMetadata {
    int channel_id = -1;  // -1 for a stitched domemaster
    std::string channel_name;
    uint64_t frame = 0;
    double sim_time_s = 0.0;
    std::string snapshot_hash;
    std::string renderer;
    double exposure = 1.0;  // read back from the file (written from the write_frame argument)
    // The display curve's white (shaders/shared/tone_curve.glsl; 0: none), applied to PNG after
    // the exposure and undone when a PNG is read; and the eye's adapted luminance (cd/m^2). Both
    // from the frame's snapshot, recorded as cupola:tone_white and cupola:adapted_cd_m2.
    double tone_white = 0.0;
    double adapted_cd_m2 = 0.0;
    // Whether the eye's night vision (shaders/shared/night_vision.glsl) at adapted_cd_m2 is part of
    // the display transform, recorded as cupola:night_vision. A PNG keeps what the eye saw: reading
    // it back does not undo night vision.
    bool night_vision = false;
    // The adaptation night vision works at: adapted_cd_m2 when it is on, 0 (off) otherwise.
    double night_adapted_cd_m2() const { return night_vision ? adapted_cd_m2 : 0.0; }
    // Whether the display also blurs the sky by the eye's acuity at night (shaders/shared/
    // night_acuity.glsl), recorded as cupola:acuity_blur; and that blur's standard deviation in
    // radians (0: none, also when night vision is off).
    bool acuity_blur = false;
    double acuity_sigma_rad() const;
};

// File name of a frame: "frame_000042.png" (six digits, more if needed).
std::string frame_file_name(uint64_t frame, const std::string& extension);

// Writes DIR/frame_NNNNNN.<fmt> for each format in {"png","exr"}; creates DIR. Returns the paths.
// Throws std::runtime_error naming the path on failure.
std::vector<std::string> write_frame(const std::string& dir, const Image& image, const FrameMetadata& meta,
                                     const std::vector<std::string>& formats, double exposure);

// Writes DIR/frame_NNNNNN.png holding exactly these bytes (no display transform), with the
// metadata attributes; creates DIR. Returns the path; throws std::runtime_error naming it.
std::string write_encoded_png(const std::string& dir, const EncodedImage& image, const FrameMetadata& meta,
                              double exposure);

// Reads an image written by write_frame (or any RGB/RGBA image) as linear float. PNG input is
// decoded from sRGB and divided by the exposure recorded in the file (1 if absent).
Image read_image(const std::string& path, FrameMetadata* meta = nullptr);

// Like read_image(), but EXR (linear) input is also divided by the recorded exposure, so that
// both formats come back as scene radiance: what the stitcher resamples before it applies the
// output exposure again.
Image read_image_radiance(const std::string& path, FrameMetadata* meta = nullptr);

// The display transform used for PNG: linear_to_srgb of display_color(exposure * linear, white).
// display_color: linear BT.709 RGB (any values, negative ones included) through the tone curve
// of white `tone_white` (shaders/shared/tone_curve.glsl; 0: none), then mapped into the unit cube
// by shaders/shared/gamut_map.glsl (a NaN component counts as 0); unchanged when inside.
glm::vec3 display_color(const glm::vec3& linear, double tone_white = 0.0);
// The same after the eye's night vision (shaders/shared/night_vision.glsl): `linear` is the exposed
// colour, `exposure` what it was exposed by, night_adapted_cd_m2 the eye's adaptation (0: off).
glm::vec3 display_color(const glm::vec3& linear, double tone_white, double exposure, double night_adapted_cd_m2);
float linear_to_srgb(float linear);
float srgb_to_linear(float encoded);

}  // namespace cupola
