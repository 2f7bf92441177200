#version 450 core
// A terrain tile (slave/passes/terrain_drawer.cpp): its vertices as floats relative to the tile's
// centre in the body-fixed frame, the centre relative to the camera in the channel frame (from
// doubles on the CPU), so nothing the GPU sees is larger than a tile. Each vertex moves toward its
// parent's shape by its own distance from the camera (shared/terrain_light.glsl, terrain_morph),
// and finds how much of the Sun it sees over the relief's horizon (terrain_sun_visibility).
layout(location = 0) in vec3 a_position;      // own shape, body frame, relative to the tile's centre
layout(location = 1) in vec3 a_parent_delta;  // parent shape minus own
layout(location = 2) in vec3 a_normal;        // unit, body frame
layout(location = 3) in vec4 a_horizon;       // packed horizon map (common/terrain/tile_horizon.hpp)
uniform mat4 u_projection;
uniform mat3 u_body_to_channel;
uniform vec3 u_centre_channel_m;  // the tile's centre relative to the camera, channel frame
uniform vec3 u_centre_body_m;     // the tile's centre from the body's centre (for the light's look-ups)
uniform float u_morph_far_m;
uniform vec3 u_sun_body;  // unit, body frame, from the body toward the Sun

out vec3 v_channel_m;  // camera -> point, channel frame
out vec3 v_body_m;     // the point from the body's centre, body frame
out vec3 v_normal;     // body frame
out float v_sun_seen;  // how much of the Sun the vertex sees over the relief (its shadows)

void main() {
    vec3 own = u_centre_channel_m + u_body_to_channel * a_position;
    float morph = terrain_morph(length(own), u_morph_far_m);
    vec3 local = a_position + (1.0 - morph) * a_parent_delta;
    v_channel_m = u_centre_channel_m + u_body_to_channel * local;
    v_body_m = u_centre_body_m + local;
    v_normal = a_normal;
    v_sun_seen = terrain_sun_visibility(a_horizon, normalize(v_body_m), u_sun_body);
    gl_Position = u_projection * vec4(v_channel_m, 1.0);
}
