#version 450 core
// The ciliary-corona rays of one source as geometry (slave/passes/glare_pass.hpp): one thin
// triangle per ray, its apex at the glare centre and its sides at the ray's azimuth +- the ray's
// half-width (0.1 cell, glare_streaks), reaching past the glare's extent. In the plane at the
// scaled distance along the centre (the billboard's plane), great circles through the centre
// are straight lines, so the triangle is exactly the ray's wedge: the rays are evaluated only
// where they are nonzero, a fifth of the circle. Vertex 3 i + k: ray i, corner k.
uniform mat4 u_projection;
uniform GlareParams u_glare;
uniform vec3 u_center;  // unit, channel frame
uniform vec3 u_e1;      // glare frame axes, channel frame
uniform vec3 u_e2;
uniform float u_reach;  // the far corners' distance from the centre, per unit scaled distance

flat out vec2 v_axis;         // (cos, sin) of the ray's azimuth in the glare frame
flat out float v_brightness;  // the ray's h at the phase

const float kScaledDistance = 100.0;  // SphereView::kScaledDistance

void main() {
    float n = glare_ray_cells(u_glare);
    float cell = float(gl_VertexID / 3);
    int corner = gl_VertexID - 3 * (gl_VertexID / 3);
    vec2 ray = glare_ray(u_glare, cell);
    float phi = (cell + ray.x) * (2.0 * CUPOLA_PI / n);
    v_axis = vec2(cos(phi), sin(phi));
    v_brightness = ray.y;
    vec3 pos = u_center;
    if (corner != 0) {
        float a = phi + (corner == 1 ? -0.1 : 0.1) * (2.0 * CUPOLA_PI / n);
        pos += u_reach * (cos(a) * u_e1 + sin(a) * u_e2);
    }
    gl_Position = u_projection * vec4(pos * kScaledDistance, 1.0);
}
