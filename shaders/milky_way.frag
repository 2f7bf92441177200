#version 450 core
// The Milky Way: each pixel's view ray turned into galactic coordinates and looked up on the map
// (shared/galactic_map.glsl), at the map level the cluster's coarsest pixel spans (the same on
// every channel), in physical surface brightness. Added to the colour (alpha 0) before the
// atmosphere, which then dims it by the air's transmittance and adds its own light, as it does
// the stars'. MILKY_WAY_AFTER_SKY: the sky was drawn first (FrameContext::sky_first), and the
// map takes the air's transmittance in front of it here; nothing shows below the horizon.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform mat3 u_channel_to_galactic;
uniform float u_latitude_extent_rad;
uniform float u_sin_latitude_extent;
uniform float u_map_lod;
uniform vec3 u_radiance;  // scene units per unit of the map
uniform sampler2D u_map;  // linear, row 0 = the top row (north galactic)
#if MILKY_WAY_AFTER_SKY
uniform AtmosphereParams u_atm;  // the air in front (SkyInFront: slave/passes/beyond_the_air.hpp)
uniform SkyInFront u_sky;
uniform sampler2D u_sky_third;
#endif

out vec4 frag_color;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    vec3 g = u_channel_to_galactic * v;
    if (abs(g.z) > u_sin_latitude_extent) discard;  // off the band: no trigonometry spent
    vec2 uv = galactic_map_uv(g, u_latitude_extent_rad);
    vec3 radiance = u_radiance * textureLod(u_map, uv, u_map_lod).rgb;
#if MILKY_WAY_AFTER_SKY
    if (atm_sky_in_front_hidden(u_atm, u_sky, v)) discard;
    radiance *= vec3(textureLod(u_sky_third, atm_sky_in_front_uv(u_atm, u_sky, v), 0.0));
#endif
    frag_color = vec4(radiance, 0.0);
}
