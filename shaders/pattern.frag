#version 450 core
// The alignment patterns (docs/ALIGNMENT.md; slave/passes/pattern_pass.hpp), replacing the scene's
// colour: PATTERN_GRID draws the dome-frame grid (shared/alignment_grid.glsl), tints the
// directions another channel's frustum also covers and writes the channel's label; PATTERN_WHITE
// and PATTERN_BLACK are uniform fields. Values are divided by the frame's exposure, so that the
// frame written (radiance x exposure) shows the pattern's own values.
const int PATTERN_GRID = 1;
const int PATTERN_WHITE = 2;
const int PATTERN_BLACK = 3;
const int MAX_OTHER_CHANNELS = 16;

uniform int u_pattern;
uniform float u_inv_exposure;
uniform vec4 u_tangents;  // this channel: (left, right, down, up)
uniform vec2 u_size;
uniform mat3 u_channel_to_dome;
uniform int u_other_count;
uniform mat3 u_other_dome_to_channel[MAX_OTHER_CHANNELS];
uniform vec4 u_other_tangents[MAX_OTHER_CHANNELS];
uniform vec3 u_overlap_tint;
uniform vec4 u_label_box;  // window pixels (origin bottom left): x0, y0, x1, y1
uniform vec3 u_label_color;
layout(binding = 0) uniform sampler2D u_label;  // coverage in .r, row 0 the text's top

layout(location = 0) out vec4 frag_color;

// Whether another channel's frustum holds the dome direction (ChannelFrustum::contains).
bool covered_by_another(vec3 dome_dir) {
    for (int i = 0; i < u_other_count; ++i) {
        if (channel_ndc_score(u_other_dome_to_channel[i] * dome_dir, u_other_tangents[i]) <= 1.0) return true;
    }
    return false;
}

vec3 label_over(vec3 color) {
    vec2 p = gl_FragCoord.xy;
    if (p.x < u_label_box.x || p.y < u_label_box.y || p.x >= u_label_box.z || p.y >= u_label_box.w) return color;
    vec2 uv = (p - u_label_box.xy) / (u_label_box.zw - u_label_box.xy);
    float coverage = textureLod(u_label, vec2(uv.x, 1.0 - uv.y), 0.0).r;
    return mix(color * 0.3, u_label_color, coverage);
}

void main() {
    if (u_pattern == PATTERN_WHITE) {
        frag_color = vec4(vec3(u_inv_exposure), 1.0);
        return;
    }
    if (u_pattern != PATTERN_GRID) {
        frag_color = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    vec2 xy = v.xy / -v.z;
    float tan_per_pixel = max((u_tangents.x + u_tangents.y) / u_size.x, (u_tangents.z + u_tangents.w) / u_size.y);
    vec3 dome_dir = normalize(u_channel_to_dome * v);
    vec3 color = alignment_grid(dome_dir, grid_pixel_rad(xy, tan_per_pixel));
    if (covered_by_another(dome_dir)) color = max(color, u_overlap_tint);
    frag_color = vec4(label_over(color) * u_inv_exposure, 1.0);
}
