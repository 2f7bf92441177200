#version 450 core
// The glare probe's occlusion query (Ekelin & Fernqvist 2009, section 3.1.1): the source's disc in a small view
// centred on it (probe frame: the source at -Z, +X/+Y the cluster-wide glare frame). Drawn once
// without depth test (the total) and once per wedge with it (the unoccluded part), after the
// occluders and before anything that does not occlude. A direction counts only in the channel
// that owns it (shared/channel_ownership.glsl), so the master's sums count nothing twice; in
// per-channel mode (the naive comparison) it counts wherever this channel's frustum holds it.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform float u_tan_radius;   // tangent of the disc's angular radius
uniform float u_depth;        // log_depth of the disc's near side
uniform int u_wedge;          // -1: the whole disc
uniform int u_owner_count;
uniform int u_self;
uniform int u_own_frustum_only;
uniform mat3 u_owner_rot[32];  // probe frame -> channel k's frame
uniform vec4 u_owner_tan[32];  // channel k's tangents (left, right, down, up)

const int WEDGES = 8;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    float x = v.x / -v.z;
    float y = v.y / -v.z;
    if (x * x + y * y >= u_tan_radius * u_tan_radius) {
        discard;
    }
    if (u_wedge >= 0) {
        float phi = atan(y, x);
        if (phi < 0.0) {
            phi += 2.0 * CUPOLA_PI;
        }
        int w = min(int(floor(phi / (2.0 * CUPOLA_PI / float(WEDGES)))), WEDGES - 1);
        if (w != u_wedge) {
            discard;
        }
    }
    if (u_own_frustum_only != 0) {
        if (channel_ndc_score(u_owner_rot[u_self] * v, u_owner_tan[u_self]) > 1.0) {
            discard;
        }
    } else {
        int owner = -1;
        float best = 1.0;
        for (int k = 0; k < u_owner_count; ++k) {
            float s = channel_ndc_score(u_owner_rot[k] * v, u_owner_tan[k]);
            if (s <= 1.0 && (owner < 0 || s < best)) {
                owner = k;
                best = s;
            }
        }
        if (owner != u_self) {
            discard;
        }
    }
    gl_FragDepth = u_depth;
}
