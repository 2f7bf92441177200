#version 450 core
// What covers a sphere on screen (slave/passes/sphere_billboard.cpp, draw_cover), by u_mode:
//   0  a billboard's four corners, a strip in scaled space (channel frame);
//   1  the whole viewport (the camera inside or on the sphere);
//   2  a fan of 26 unit directions over the sphere's cap (slave/passes/cap_cover.hpp). Every
//      direction is projected with depth 0, so the only clipping is at the eye plane (w = 0) and
//      the sides: a fan triangle that reaches behind the camera covers exactly its directions in
//      front, and none is lost to the near or far plane.
uniform vec3 u_corners[4];
uniform vec3 u_fan[26];
uniform mat4 u_projection;
uniform int u_mode;

void main() {
    if (u_mode == 1) {
        vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
        gl_Position = vec4(c, 0.0, 1.0);
    } else if (u_mode == 2) {
        vec4 p = u_projection * vec4(u_fan[gl_VertexID], 1.0);
        gl_Position = vec4(p.xy, 0.0, p.w);
    } else {
        gl_Position = u_projection * vec4(u_corners[gl_VertexID], 1.0);
    }
}
