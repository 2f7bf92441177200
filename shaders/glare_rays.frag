#version 450 core
// The rays of one source inside their wedges (glare_rays.vert): glare_ray_peak x h x tri, with
// the ray's triangular profile tri from the azimuth relative to the ray's own axis, at full
// resolution and with the contrast faded where a ray is narrower than about a pixel
// (glare_ray_contrast), as in glare.frag.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform GlareParams u_glare;
uniform vec3 u_center;
uniform vec3 u_e1;
uniform vec3 u_e2;
uniform vec3 u_irradiance;

flat in vec2 v_axis;
flat in float v_brightness;

layout(location = 0) out vec4 frag_color;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    float theta = angle_between_units(v, u_center);
    float x = dot(v, u_e1);
    float y = dot(v, u_e2);
    float along = x * v_axis.x + y * v_axis.y;
    float across = y * v_axis.x - x * v_axis.y;
    float cells = atan(across, along) * (glare_ray_cells(u_glare) * 0.5 / CUPOLA_PI);
    float tri = max(0.0, 1.0 - abs(cells) * 10.0);
    GlareParams p = u_glare;
    p.streak_contrast = glare_ray_contrast(u_glare, theta, length(fwidth(v)));
    frag_color = vec4(u_irradiance * (glare_ray_peak(p, theta) * v_brightness * tri), 0.0);
}
