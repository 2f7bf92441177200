#version 450 core
// A terrain tile as depth alone (slave/passes/terrain_drawer.hpp, draw_depth): the logarithmic
// depth of its true distance, as the glare probe's other occluders write it.
in vec3 v_channel_m;  // camera -> point, channel frame (terrain.vert)

void main() { gl_FragDepth = log_depth(length(v_channel_m)); }
