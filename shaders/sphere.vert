#version 450 core
// A viewpoint-oriented billboard around a sphere (corners computed on the CPU in scaled space,
// channel frame), or the whole viewport when the camera is too close for a billboard.
uniform vec3 u_corners[4];
uniform mat4 u_projection;
uniform int u_fullscreen;

void main() {
    if (u_fullscreen != 0) {
        vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
        gl_Position = vec4(c, 0.0, 1.0);
    } else {
        gl_Position = u_projection * vec4(u_corners[gl_VertexID], 1.0);
    }
}
