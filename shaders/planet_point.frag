#version 450 core
// A planet's point: its PSF integrated exactly over the pixel (star_box_fraction, as stars.frag),
// added to the colour (alpha 0: the coverage stays). Hidden where a nearer body covers the pixel
// centre (u_occluders: an occultation by the Moon). POINT_AFTER_SKY: the sky was drawn first and
// the point takes the air's transmittance in front of it here (beyond_the_air.hpp).
flat in vec2 v_t;
flat in vec2 v_sigma_t;

uniform vec4 u_tangents;  // left, right, down, up
uniform vec2 u_size;
uniform vec3 u_color;
uniform int u_occluder_count;
uniform vec4 u_occluders[4];  // nearer bodies: unit direction (channel frame), angular radius
#if POINT_AFTER_SKY
uniform AtmosphereParams u_atm;
uniform SkyInFront u_sky;
uniform sampler2D u_sky_third;
#endif

out vec4 frag_color;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    for (int i = 0; i < u_occluder_count; ++i) {
        if (angle_between_units(v, u_occluders[i].xyz) < u_occluders[i].w) discard;
    }
    vec2 px = floor(gl_FragCoord.xy);
    vec2 span = vec2(u_tangents.x + u_tangents.y, u_tangents.z + u_tangents.w) / u_size;
    vec2 lo = vec2(-u_tangents.x, -u_tangents.z) + px * span;
    vec2 hi = lo + span;
    vec2 c = 0.5 * (lo + hi);
    float q = 1.0 + dot(c, c);
    vec3 radiance = u_color * (star_box_fraction(v_t, v_sigma_t, lo, hi) / (span.x * span.y / (q * sqrt(q))));
#if POINT_AFTER_SKY
    if (atm_sky_in_front_hidden(u_atm, u_sky, v)) discard;
    radiance *= vec3(textureLod(u_sky_third, atm_sky_in_front_uv(u_atm, u_sky, v), 0.0));
#endif
    frag_color = vec4(radiance, 0.0);
}
