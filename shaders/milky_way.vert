#version 450 core
// The Milky Way's band as a ribbon of triangles on the unit sphere (passes/milky_way_pass): only
// the pixels near the band are shaded. The fragment shader finds each pixel's own direction.
layout(location = 0) in vec3 a_world;  // unit, world frame
uniform mat3 u_world_to_channel;
uniform mat4 u_projection;

void main() {
    gl_Position = u_projection * vec4(u_world_to_channel * a_world, 1.0);
}
