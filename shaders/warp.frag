#version 450 core
// The projector pass (slave/output/warp_pass.hpp says why it is a per-pixel lookup and how the
// footprint filter works): raster pixel -> bilinear grid lookup -> content (u, v), filtered over
// the pixel's footprint (and at night blurred by the eye's acuity) -> exposure -> night vision ->
// display curve (shared/tone_curve.glsl) -> gamut map, blend
// and black lift -> encode (shared/projector_blend.glsl).
// Conventions: common/calibration/projector_warp.hpp (raster y from the top, grid in fill layout,
// content v up).
uniform sampler2D u_content;  // linear radiance, v up (texture row 0 = content bottom)
uniform sampler2D u_grid;     // columns x rows: (u, v, intensity, -); texel (i, j) = grid point, j = 0 the top
uniform sampler2D u_alpha;    // over the raster, row 0 the top
uniform sampler2D u_beta;
uniform vec2 u_raster;        // raster width, height in pixels
uniform vec2 u_content_size;  // content width, height in texels
uniform float u_exposure;
uniform float u_tone_white;   // the display curve's white (shared/tone_curve.glsl); 0: none
uniform float u_night_adapted_cd_m2;  // the eye's adaptation for night vision; 0: none
uniform float u_acuity_sigma_rad;     // the eye's acuity blur (shared/night_acuity.glsl); 0: none
uniform vec4 u_content_tan;           // the content frustum's tangents: left, right, down, up (outward)
uniform mat3 u_content_to_dome;       // the content's camera frame -> the dome frame
uniform float u_gamma;
uniform int u_encode;         // PROJECTOR_ENCODE_*
uniform int u_max_taps;       // footprint box filter: most taps per axis (1: one tap)
uniform bool u_identity;      // no calibration: u_grid is not read

layout(location = 0) out vec4 out_linear;
layout(location = 1) out vec4 out_encoded;

struct WarpPoint {
    bool shown;
    vec2 uv;
    float intensity;
    vec2 d_dx;  // d(u, v) per raster pixel to the right
    vec2 d_dy;  // d(u, v) per raster pixel down
};

// p: raster position in pixels, y from the top. Beyond the outer grid points (half a cell in
// fill layout) the edge value holds, as common/calibration/reference_warp.hpp rules.
WarpPoint warp_lookup(vec2 p) {
    WarpPoint w;
    if (u_identity) {  // no calibration: the raster is the content
        w.shown = true;
        w.uv = vec2(p.x / u_raster.x, 1.0 - p.y / u_raster.y);
        w.intensity = 1.0;
        w.d_dx = vec2(1.0 / u_raster.x, 0.0);
        w.d_dy = vec2(0.0, -1.0 / u_raster.y);
        return w;
    }
    ivec2 n = textureSize(u_grid, 0);
    vec2 g_free = p * vec2(n) / u_raster - 0.5;  // grid point (i, j) sits at g = (i, j)
    vec2 g = clamp(g_free, vec2(0.0), vec2(n - 1));
    ivec2 i0 = min(ivec2(floor(g)), n - 2);
    vec2 f = g - vec2(i0);
    vec4 p00 = texelFetch(u_grid, i0, 0);
    vec4 p10 = texelFetch(u_grid, i0 + ivec2(1, 0), 0);
    vec4 p01 = texelFetch(u_grid, i0 + ivec2(0, 1), 0);
    vec4 p11 = texelFetch(u_grid, i0 + ivec2(1, 1), 0);
    w.shown = !(any(isnan(p00.xy)) || any(isnan(p10.xy)) || any(isnan(p01.xy)) || any(isnan(p11.xy)));
    vec4 v = mix(mix(p00, p10, f.x), mix(p01, p11, f.x), f.y);
    w.uv = v.xy;
    w.intensity = v.z;
    // The Jacobian of the bilinear patch (0 along an axis where the edge value holds).
    vec2 inside = vec2(equal(g, g_free));
    w.d_dx = mix(p10.xy - p00.xy, p11.xy - p01.xy, f.y) * (inside.x * float(n.x) / u_raster.x);
    w.d_dy = mix(p01.xy - p00.xy, p11.xy - p10.xy, f.x) * (inside.y * float(n.y) / u_raster.y);
    w.shown = w.shown && all(greaterThanEqual(w.uv, vec2(0.0))) && all(lessThanEqual(w.uv, vec2(1.0)));
    return w;
}

// The mean of an n x n box of bilinear taps over the parallelogram the pixel maps onto.
vec3 filtered_content(WarpPoint w) {
    float side = max(length(w.d_dx * u_content_size), length(w.d_dy * u_content_size));
    int n = clamp(int(ceil(side - 1e-3)), 1, u_max_taps);
    vec3 sum = vec3(0.0);
    for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
            vec2 o = (vec2(a, b) + 0.5) / float(n) - 0.5;
            sum += textureLod(u_content, w.uv + o.x * w.d_dx + o.y * w.d_dy, 0.0).rgb;
        }
    }
    return sum / float(n * n);
}

// The content's perspective projection, as common/projection/channel_frustum.cpp: (u, v), v up,
// to and from dome directions.
vec3 content_direction(vec2 uv) {
    return normalize(u_content_to_dome * channel_ray(uv, vec2(1.0), u_content_tan));
}

vec2 content_uv(vec3 dome_dir) {
    vec3 c = transpose(u_content_to_dome) * dome_dir;
    if (c.z >= 0.0) return vec2(-1.0);
    vec2 t = c.xy / -c.z;
    return (t + u_content_tan.xz) / (u_content_tan.xz + u_content_tan.yw);
}

// The eye's acuity blur: the weighted mean of the taps around the pixel's direction that fall on
// the content (common/dome/acuity_blur.hpp, the same rule on the CPU).
vec3 acuity_blurred_content(WarpPoint w) {
    vec3 d = content_direction(w.uv);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int k = 0; k < ACUITY_TAPS; ++k) {
        WarpPoint t = w;
        t.uv = content_uv(acuity_tap_direction(d, u_acuity_sigma_rad, k));
        if (any(lessThan(t.uv, vec2(0.0))) || any(greaterThan(t.uv, vec2(1.0)))) continue;
        float wk = acuity_tap(k).z;
        sum += wk * filtered_content(t);
        weight += wk;
    }
    return weight > 0.0 ? sum / weight : filtered_content(w);
}

void main() {
    vec2 p = vec2(gl_FragCoord.x, u_raster.y - gl_FragCoord.y);
    WarpPoint w = warp_lookup(p);
    vec2 t = p / u_raster;
    float alpha = textureLod(u_alpha, t, 0.0).r;
    float beta = textureLod(u_beta, t, 0.0).r;
    // Not shown: black content, still lifted to the projector's black level like every pixel.
    vec3 seen = u_acuity_sigma_rad > 0.0 ? acuity_blurred_content(w) : filtered_content(w);
    vec3 exposed = night_vision(seen * u_exposure, u_exposure, u_night_adapted_cd_m2);
    vec3 content = w.shown ? tone_curve(exposed, u_tone_white) : vec3(0.0);
    vec3 c = projector_blend(content, alpha, w.intensity, beta);
    out_linear = vec4(c, 1.0);
    out_encoded = vec4(projector_encode(c, u_gamma, u_encode), 1.0);
}
