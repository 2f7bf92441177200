#version 450 core
// One texel per catalogue star: how much of it the eye sees against the sky behind it
// (shared/star_visibility.glsl), from the sky-view table every channel shares and inputs in the
// world frame. Rendered only when those inputs change (slave/passes/star_sky_weights.hpp); the
// star sprites read their texel (stars.vert), which costs a CPU rasteriser far less than a
// look-up per star per frame in its vertex stage. It also finds the last star with any weight
// (the stars run from bright to faint): the star draw is indirect, and takes that as its count,
// so a daytime sky draws no star at all and no CPU ever waits for the GPU.
uniform sampler2D u_stars;  // per texel: the star's world direction and its visual magnitude
uniform AtmosphereParams u_atm;
uniform sampler2D u_sky_phased;  // the sky-view table's parts (shared/atmosphere_sky_view.glsl)
uniform sampler2D u_sky_mie;
uniform sampler2D u_sky_third;
uniform vec2 u_sky_size;
uniform float u_sky_d_m;        // camera -> planet centre, metres
uniform vec3 u_sky_center_dir;  // unit, world frame: camera -> planet centre
uniform vec3 u_sky_sun;         // unit, world frame: planet centre -> Sun
uniform float u_sky_to_cd_m2;   // the table's values to cd/m^2
uniform float u_night_sky_cd_m2;  // the night sky's own glow at the zenith (shared/night_sky.glsl)
uniform sampler2D u_moon_phased;  // the Moon's sky-view table (common/atmosphere/moonlit_sky.hpp), when
uniform sampler2D u_moon_mie;     // u_moon_ratio > 0
uniform sampler2D u_moon_third;
uniform vec3 u_moon;              // unit, world frame: camera -> Moon
uniform float u_moon_ratio;       // its luminous irradiance over the Sun's; 0: no moonlit sky
uniform int u_star_count;       // the stars to judge: those the magnitude limits leave, a prefix
uniform int u_width;            // texels per row
// The star draw's indirect command (glDrawArraysIndirect), count 0 when this pass starts.
layout(std430, binding = 0) buffer StarDraw {
    uint count;
    uint instance_count;
    uint first;
    uint base_instance;
} u_draw;

out vec4 frag_color;

void main() {
    vec4 star = texelFetch(u_stars, ivec2(gl_FragCoord.xy), 0);
    vec4 light = star_sky_light(u_atm, u_sky_phased, u_sky_mie, u_sky_third, u_sky_size, u_sky_d_m, star.xyz,
                                u_sky_center_dir, u_sky_sun);
    // The Moon's sky behind the star: the same look-up in the Moon's own table, seen against the
    // Moon, times its luminous irradiance over the Sun's (0 where the ray meets the ground).
    if (u_moon_ratio > 0.0 && light.w >= 0.0)
        light.w += u_moon_ratio * max(star_sky_light(u_atm, u_moon_phased, u_moon_mie, u_moon_third, u_sky_size,
                                                     u_sky_d_m, star.xyz, u_sky_center_dir, u_moon).w,
                                      0.0);
    int index = int(gl_FragCoord.y) * u_width + int(gl_FragCoord.x);
    float glow_cd_m2 = u_night_sky_cd_m2 * night_sky_gradient(dot(star.xyz, -u_sky_center_dir));
    float weight = index < u_star_count
                       ? star_sky_weight_over(star_sky_behind_of(light), u_sky_to_cd_m2, glow_cd_m2, star.w)
                       : 0.0;
    if (weight > 0.0) atomicMax(u_draw.count, uint(index + 1));
    // The weight, and the weight times the air's transmittance in front of the star (what a star
    // drawn after the sky takes: the atmosphere's look-up no longer multiplies it).
    frag_color = vec4(weight, weight * vec3(light));
}
