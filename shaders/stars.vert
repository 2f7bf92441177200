#version 450 core
// Star sprites: one GL point per catalogue star, sized from the local pixel scale so that it
// covers the PSF out to where the star can still change a display pixel: the angle r at which
// peak * exposure * exp(-r^2 / (2 sigma^2)) falls to u_min_display (the visibility criterion of
// slave/passes/star_pass.hpp), so a faint star's sprite is small and a bright one's large. The
// reach is an angle from cluster-wide values (flux, sigma, the snapshot's exposure): every
// channel covers the same directions. The fragment shader integrates the PSF over each pixel.
// With a sky (u_sky_on), a star shows only as far as the eye could see it against the sky behind
// it (shared/star_visibility.glsl, Schaefer's threshold): its weight, judged in the world frame
// from the sky-view table every channel shares (star_weights.frag), so a star is seen alike on
// every channel. When the sky is drawn first (FrameContext::sky_first), the star also takes the
// air's transmittance in front of it from there, one value per star.
layout(location = 0) in vec3 a_dir;   // unit direction, world frame
layout(location = 1) in float a_flux; // zero_mag_flux * 10^(-0.4 V), scene units x sr
layout(location = 2) in float a_bv;   // B-V colour index
layout(location = 3) in vec4 a_sky_weight;  // slave/passes/star_sky_weights.hpp: the weight, and
                                            // the weight times the air's transmittance (rgb)

uniform mat3 u_world_to_channel;
uniform mat4 u_projection;      // the channel frustum widened by a guard band
uniform vec2 u_px_per_tangent;  // pixels per unit of tangent-plane coordinate (x, y)
uniform float u_sigma_rad;      // PSF sigma, radians
uniform float u_exposure;       // the snapshot's; <= 0: u_fixed_reach_sigma for every star
uniform float u_min_display;    // the display value below which a pixel cannot change
uniform float u_fixed_reach_sigma;
uniform vec3 u_occluder_dir;    // unit, channel frame: the largest body on screen
uniform float u_occluder_rad;   // its angular radius; <= 0: none
uniform float u_pixel_rad;      // the widest angle a pixel spans
uniform int u_sky_on;           // 0: no sky to judge the stars by; 1: the weight; 2: the weight
                                // and the air in front (the sky was drawn first)
uniform float u_twinkle_sigma_zenith;  // shared/star_twinkle.glsl; 0: steady stars
uniform vec3 u_twinkle_zenith;         // unit, world frame; zero: every star at airmass 1
uniform float u_twinkle_time_s;        // the snapshot's twinkle clock

flat out vec3 v_color;    // flux times the unit-luminance B-V colour
flat out vec2 v_t;        // tangent-plane point of the star
flat out vec2 v_sigma_t;  // tangent-plane sigmas of its PSF

// How much of the star the eye sees against the sky (1 without one).
float sky_weight() {
    if (u_sky_on == 0) return 1.0;
    return a_sky_weight.x;
}

// What the star's light is multiplied by here: its weight, and when the sky was drawn first (the
// atmosphere's look-up then no longer multiplies what lies behind it) the air's transmittance.
vec3 sky_factor(float weight) {
    if (u_sky_on == 2) return vec3(a_sky_weight.yzw);
    return vec3(weight);
}

// The star's twinkle factor: a function of its index, the clock and its airmass in the world,
// the same on every channel (slave/passes/star_pass.hpp: StarTwinkle).
float twinkle() {
    if (!(u_twinkle_sigma_zenith > 0.0)) return 1.0;
    float airmass = dot(u_twinkle_zenith, u_twinkle_zenith) > 0.0 ? twinkle_airmass(dot(a_dir, u_twinkle_zenith)) : 1.0;
    return twinkle_factor(uint(gl_VertexID), u_twinkle_time_s, twinkle_sigma(u_twinkle_sigma_zenith, airmass));
}

void main() {
    vec3 d = u_world_to_channel * a_dir;
    float weight = sky_weight();
    v_color = sky_factor(weight) * twinkle() * a_flux * bv_to_linear_srgb(a_bv);
    gl_Position = u_projection * vec4(d, 1.0);
    float zc = min(d.z, -1e-3);
    float tx = d.x / -zc;
    float ty = d.y / -zc;
    v_t = vec2(tx, ty);
    v_sigma_t = star_tangent_sigma(v_t, u_sigma_rad);
    // Pixels per radian: the tangent plane stretches angles by up to 1 + tan^2 off axis.
    float px_per_rad = max(u_px_per_tangent.x, u_px_per_tangent.y) * (1.0 + tx * tx + ty * ty);
    float reach_sigma = u_fixed_reach_sigma;
    if (u_exposure > 0.0) {
        float peak = max(v_color.r, max(v_color.g, v_color.b)) / (2.0 * CUPOLA_PI * u_sigma_rad * u_sigma_rad);
        reach_sigma = sqrt(2.0 * log(max(peak * u_exposure / u_min_display, 1.0)));
    }
    // Every pixel centre within the reach of the star's point, plus one pixel for the pixel's extent.
    gl_PointSize = clamp(ceil(2.0 * reach_sigma * u_sigma_rad * px_per_rad) + 2.0, 1.0, 255.0);
    // Wholly behind the occluder (its reach and two pixels inside the disc's edge): the body pass,
    // or the atmosphere relighting the ground, paints over it, so it is not drawn (a point outside
    // the clip volume is discarded).
    float inside_rad = u_occluder_rad - reach_sigma * u_sigma_rad - 2.0 * u_pixel_rad;
    // Not seen against the sky: not drawn either.
    if (weight <= 0.0 || (u_occluder_rad > 0.0 && inside_rad > 0.0 && dot(d, u_occluder_dir) > cos(inside_rad))) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    }
}
