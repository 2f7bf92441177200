#include "passes/milky_way_pass.hpp"

#include <erfa.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "passes/body_map.hpp"
#include "passes/sphere_billboard.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {

constexpr double kArcsec2_sr = (std::numbers::pi / (180.0 * 3600.0)) * (std::numbers::pi / (180.0 * 3600.0));

// The luminance below which 99 % of the map's texels lie.
double brightest_percentile(const BodyImage& image) {
    std::vector<float> lum(static_cast<size_t>(image.width) * image.height);
    for (size_t i = 0; i < lum.size(); ++i)
        lum[i] = shading::rec709_luminance(glm::vec3(image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]));
    auto at = lum.begin() + static_cast<std::ptrdiff_t>(lum.size() * 99 / 100);
    std::nth_element(lum.begin(), at, lum.end());
    return *at;
}

bool is_grey(const BodyImage& image) {
    for (size_t i = 0; i + 2 < image.rgb.size(); i += 3)
        if (image.rgb[i] != image.rgb[i + 1] || image.rgb[i] != image.rgb[i + 2]) return false;
    return true;
}

double brightest_texel(const BodyImage& image) {
    float peak = 0.0f;
    for (float v : image.rgb) peak = std::max(peak, v);
    return peak;
}

}  // namespace

glm::dmat3 MilkyWayPass::world_to_galactic() {
    // Columns of galactic -> ICRS are the galactic axes in the ICRS; the inverse is the transpose.
    // A constant of the frame: worked out once, not for every frame and channel.
    static const glm::dmat3 rotation = [] {
        glm::dmat3 to_world(1.0);
        const double axes[3][2] = {{0.0, 0.0}, {std::numbers::pi / 2.0, 0.0}, {0.0, std::numbers::pi / 2.0}};
        for (int k = 0; k < 3; ++k) {
            double ra = 0.0, dec = 0.0, p[3];
            eraG2icrs(axes[k][0], axes[k][1], &ra, &dec);
            eraS2c(ra, dec, p);
            to_world[k] = glm::dvec3(p[0], p[1], p[2]);
        }
        return glm::transpose(to_world);
    }();
    return rotation;
}

// The band |b| <= extent (plus a margin the fragment shader trims) as triangles on the unit sphere,
// world frame: 2-degree columns in longitude, rows of at most 10 degrees in latitude, so that no
// triangle is wide enough for its straight edges to stray from the sphere.
std::vector<float> band_ribbon(double extent_rad) {
    const double top = std::min(extent_rad + glm::radians(0.2), std::numbers::pi / 2.0);
    const int columns = 180, rows = std::max(1, static_cast<int>(std::ceil(2.0 * top / glm::radians(10.0))));
    const glm::dmat3 to_world = glm::transpose(MilkyWayPass::world_to_galactic());
    auto corner = [&](int i, int j) {
        const double l = 2.0 * std::numbers::pi * i / columns, b = -top + 2.0 * top * j / rows;
        return glm::vec3(to_world * glm::dvec3(std::cos(b) * std::cos(l), std::cos(b) * std::sin(l), std::sin(b)));
    };
    std::vector<float> out;
    out.reserve(static_cast<size_t>(columns) * rows * 18);
    for (int i = 0; i < columns; ++i)
        for (int j = 0; j < rows; ++j)
            for (const auto& [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}}) {
                const glm::vec3 p = corner(i + di, j + dj);
                out.insert(out.end(), {p.x, p.y, p.z});
            }
    return out;
}

MilkyWayPass::MilkyWayPass(const MilkyWayConfig& config, double zero_mag_flux, double coarsest_pixel_rad)
    : program_("milky_way.vert", "milky_way.frag", "#define MILKY_WAY_AFTER_SKY 0\n"),
      after_sky_program_("milky_way.vert", "milky_way.frag", "#define MILKY_WAY_AFTER_SKY 1\n"),
      ribbon_({3}) {
    BodyMap map = take_body_map(config.texture, glm::dvec3(1.0));
    const double p99 = brightest_percentile(map.image);
    if (!(p99 > 0.0))
        throw std::runtime_error("milky way map \"" + config.texture +
                                 "\" is black in 99 % of its texels: nothing to scale its surface brightness by");
    radiance_per_unit_ = zero_mag_flux * std::pow(10.0, -0.4 * config.surface_brightness) / kArcsec2_sr / p99;
    peak_radiance_ = radiance_per_unit_ * brightest_texel(map.image);
    latitude_extent_rad_ = config.latitude_extent_deg > 0.0 ? glm::radians(config.latitude_extent_deg)
                                                            : std::numbers::pi * map.image.height / map.image.width;
    const double texels = coarsest_pixel_rad * map.image.width / (2.0 * std::numbers::pi);
    map_lod_ = std::max(0.0, std::log2(std::max(texels, 1e-30)));
    map_ = std::make_unique<GlTexture>(map.image.width, map.image.height, map.image.rgb, map.mips,
                                       is_grey(map.image) ? GlTexture::Channels::Grey : GlTexture::Channels::Rgb);
    // One level: the level is one for the whole cluster and never changes, so nothing blends
    // between two (half the texel fetches).
    glTextureParameteri(map_->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    ribbon_.upload(band_ribbon(latitude_extent_rad_));
}

// Whether any direction the channel sees can lie within the band: the channel's centre is less
// than its half-diagonal plus the band's half-width from the galactic equator.
bool MilkyWayPass::band_can_be_seen(const FrameContext& frame) const {
    const ChannelFrustum& f = *frame.view.frustum;
    const glm::dvec3 centre =
        glm::normalize(glm::dvec3(0.5 * (f.tan_right() - f.tan_left()), 0.5 * (f.tan_up() - f.tan_down()), -1.0));
    double reach = 0.0;
    for (const double x : {-f.tan_left(), f.tan_right()})
        for (const double y : {-f.tan_down(), f.tan_up()})
            reach = std::max(
                reach, std::acos(std::clamp(glm::dot(centre, glm::normalize(glm::dvec3(x, y, -1.0))), -1.0, 1.0)));
    const glm::dvec3 g = world_to_galactic() * (frame.view.channel_to_world * centre);
    const double latitude = std::asin(std::clamp(g.z, -1.0, 1.0));
    return std::abs(latitude) - reach < latitude_extent_rad_;
}

int MilkyWayPass::prepare_at(const FrameContext& frame, bool after_sky) {
    if (after_sky && !sky_in_front_)
        throw std::logic_error("milky way: drawn after the sky without an atmosphere to take the air in front from");
    frame_ = &frame;
    after_sky_ = after_sky;
    const double exposure = frame.snap->settings.exposure;
    if (exposure > 0.0 && peak_radiance_ * exposure < kMinDisplay) return 0;
    return band_can_be_seen(frame) ? 1 : 0;
}

void MilkyWayPass::draw(const PassInputs&, int) {
    const GlProgram& p = after_sky_ ? after_sky_program_ : program_;
    const ChannelView& view = frame_->view;
    p.use();
    p.set("u_world_to_channel", glm::mat3(view.world_to_channel));
    p.set("u_projection", glm::mat4(view.frustum->projection(0.1, 10.0)));
    p.set("u_tangents", view.tangents());
    p.set("u_size", view.size());
    p.set("u_channel_to_galactic", glm::mat3(world_to_galactic() * view.channel_to_world));
    p.set("u_latitude_extent_rad", static_cast<float>(latitude_extent_rad_));
    p.set("u_sin_latitude_extent", static_cast<float>(std::sin(latitude_extent_rad_)));
    p.set("u_map_lod", static_cast<float>(map_lod_));
    p.set("u_radiance", glm::vec3(static_cast<float>(radiance_per_unit_)));
    p.set("u_map", 0);
    map_->bind(0);
    if (after_sky_) sky_in_front_->set_sky_in_front(p);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    ribbon_.bind();
    glDrawArrays(GL_TRIANGLES, 0, ribbon_.vertex_count());
    glDisable(GL_BLEND);
    gl::check("milky way pass");
}

}  // namespace cupola
