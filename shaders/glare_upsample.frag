#version 450 core
// The glare's halo target added to the full-resolution image (slave/passes/glare_pass.hpp):
// one bilinear fetch per pixel. The texture coordinate of a pixel comes from its position
// relative to the channel's axis (GlareHaloGrid), and the grid has a guard band of texels
// beyond the channel's edges, so no fetch is clamped at an edge.
uniform sampler2D u_halo;
uniform vec4 u_halo_map;  // texture coordinate = gl_FragCoord.xy * u_halo_map.xy + u_halo_map.zw

layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(textureLod(u_halo, gl_FragCoord.xy * u_halo_map.xy + u_halo_map.zw, 0.0).rgb, 0.0);
}
