#pragma once
// The Milky Way (shaders/milky_way.frag): a map of the sky in galactic coordinates
// (MilkyWayConfig), turned into place by the IAU galactic frame as the Hipparcos catalogue defines
// it in the ICRS (ESA 1997, volume 1, section 1.5.3; ERFA's eraG2icrs), in physical surface
// brightness: the map's brightest 1 % of texels have the configured V magnitudes per square
// arcsecond, converted with the star field's zero_mag_flux, so that the band and the stars agree.
//
// Drawn before the atmosphere like the stars (or after a sky drawn first, taking the air's
// transmittance in front of it: beyond_the_air.hpp), so the air dims it and outshines it by day.
// Computed only where it can show: not at all when the frame's exposure cannot lift its brightest
// texel to kMinDisplay (by day), nor when the channel's view cannot reach the band; and in view,
// only over a ribbon of triangles around the band (milky_way.vert), not the whole channel. The
// map level follows the cluster's coarsest pixel, the same on every channel.
#include <glm/glm.hpp>

#include <memory>
#include <string>

#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/beyond_the_air.hpp"

namespace cupola {

class MilkyWayPass : public BeyondTheAirPass {
public:
    MilkyWayPass(const MilkyWayConfig& config, double zero_mag_flux, double coarsest_pixel_rad);

    std::string name() const override { return "milky way"; }
    PassIo io() const override { return {.writes_color = true}; }
    int prepare_at(const FrameContext& frame, bool after_sky) override;
    void draw(const PassInputs& in, int step) override;
    // Who gives the air in front when the sky was drawn first (the atmosphere pass).
    void set_sky_in_front(const SkyInFrontSource* sky) { sky_in_front_ = sky; }

    // Scene units of radiance per unit of the map, and the brightest radiance the map gives.
    double radiance_per_map_unit() const { return radiance_per_unit_; }
    double peak_radiance() const { return peak_radiance_; }
    double latitude_extent_rad() const { return latitude_extent_rad_; }
    // The rotation from the world frame (ICRS axes) to the galactic frame (x toward l = 0, b = 0,
    // z toward the north galactic pole).
    static glm::dmat3 world_to_galactic();
    static constexpr double kMinDisplay = 1.0 / 8192.0;  // as the stars': under half an sRGB code value

private:
    bool band_can_be_seen(const FrameContext& frame) const;

    std::unique_ptr<GlTexture> map_;
    GlProgram program_, after_sky_program_;
    GlVertexBuffer ribbon_;  // the band's triangles (band_ribbon)
    double radiance_per_unit_ = 0.0, peak_radiance_ = 0.0, latitude_extent_rad_ = 0.0, map_lod_ = 0.0;
    const SkyInFrontSource* sky_in_front_ = nullptr;
    const FrameContext* frame_ = nullptr;
    bool after_sky_ = false;
};

}  // namespace cupola
