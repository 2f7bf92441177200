// Eclipse shadows of spherical casters (shared by GLSL and C++). Everything is in angular terms,
// normalised by the Sun's apparent radius: a = occluder radius / Sun radius (the occluder's
// apparent disc), s = centre separation / Sun radius. Contacts are at s = 1 + a (first/last)
// and s = |1 - a| (second/third); s < a - 1 is totality (umbra), s < 1 - a annularity
// (antumbra, a point beyond the umbra apex). Every function returns the visible fraction of the
// Sun's light in [0, 1] and never increases as the discs close (s decreasing).

// The apparent discs of the Sun and one caster seen from a point; to_sun_m and to_caster_m run
// from the point to the centres, radii in the same unit (metres everywhere in Cupola; only ratios
// enter, so any one length unit gives the same discs). A caster behind the point or beyond the
// Sun cannot occlude: s is set past first contact. Angles use asin of ratios and the chord
// (angle_between_units, star_psf.glsl), never acos of a dot product (exact for the 0.25-degree
// discs of the Sun and Moon in float).
EclipseDiscs eclipse_discs(vec3 to_sun_m, float sun_radius_m, vec3 to_caster_m, float caster_radius_m) {
    EclipseDiscs d;
    float ds = length(to_sun_m);
    float dc = length(to_caster_m);
    d.sun_radius_rad = asin(clamp(sun_radius_m / ds, 0.0, 1.0));
    float rc = asin(clamp(caster_radius_m / max(dc, caster_radius_m), 0.0, 1.0));
    d.ratio = rc / d.sun_radius_rad;
    vec3 us = to_sun_m / ds;
    vec3 uc = to_caster_m / max(dc, 1e-30);
    float sep = angle_between_units(us, uc);
    d.separation = sep / d.sun_radius_rad;
    if (dc - caster_radius_m >= ds || dot(us, uc) <= 0.0) {
        d.separation = d.ratio + 2.0;  // cannot occlude
    }
    return d;
}

// 16-point Gauss-Legendre rule on [-1, 1]: node and weight of the pair i = 0..7 (+-x).
vec2 eclipse_gauss_legendre16(int i) {
    switch (i) {
        case 0: return vec2(0.0950125098376374, 0.1894506104550685);
        case 1: return vec2(0.2816035507792589, 0.1826034150449236);
        case 2: return vec2(0.4580167776572274, 0.1691565193950025);
        case 3: return vec2(0.6178762444026438, 0.1495959888165767);
        case 4: return vec2(0.7554044083550030, 0.1246289712555339);
        case 5: return vec2(0.8656312023878318, 0.0951585116824928);
        case 6: return vec2(0.9445750230732326, 0.0622535239386479);
        default: return vec2(0.9894009349916499, 0.0271524594117541);
    }
}

// Flux of the linear limb-darkened disc (radius 1, I(r) = 1 - u (1 - sqrt(1 - r^2))) inside
// radius c: pi (1 - u) c^2 + u (2 pi / 3) (1 - (1 - c^2)^(3/2)).
float eclipse_disc_flux(float c, float u) {
    float c2 = clamp(c * c, 0.0, 1.0);
    float m = 1.0 - c2;
    return CUPOLA_PI * (1.0 - u) * c2 + u * (2.0 * CUPOLA_PI / 3.0) * (1.0 - m * sqrt(m));
}

// Nodes of the exact mode's ring quadrature: the 16-point Gauss-Legendre rule above, moved to
// phi in [0, pi] (phi = pi/2 (1 -+ x_i)) and folded with the substitution r = lo + w sin^2(phi/2).
// Pair i returns (t, 1 - t, W): t = sin^2(phi/2) = (1 - sin(pi x_i / 2)) / 2 is the node's
// position in the ring as a fraction of its width (its mirror node sits at 1 - t, same weight),
// W = w_i (pi/4) cos(pi x_i / 2) = w_i (pi/2) sin(phi/2) cos(phi/2) the weight times dr/dphi / w.
// Tabulated (in double) so that no node position is rounded through 1 - cos(phi) in float.
vec3 eclipse_ring_node(int i) {
    switch (i) {
        case 0: return vec3(4.2565406705e-01, 5.7434593295e-01, 1.4714010268e-01);
        case 1: return vec3(2.8597146821e-01, 7.1402853179e-01, 1.2961280458e-01);
        case 2: return vec3(1.7051405730e-01, 8.2948594270e-01, 9.9929387812e-02);
        case 3: return vec3(8.7399563787e-02, 9.1260043621e-01, 6.6364342243e-02);
        case 4: return vec3(3.6452555606e-02, 9.6354744439e-01, 3.6689300323e-02);
        case 5: return vec3(1.1095931029e-02, 9.8890406897e-01, 1.5657646149e-02);
        case 6: return vec3(1.8937230688e-03, 9.9810627693e-01, 4.2513850941e-03);
        default: return vec3(6.9295469669e-05, 9.9993070453e-01, 3.5503112098e-04);
    }
}

// Exact mode: visible fraction of the limb-darkened Sun behind an occluder disc (a, s), from
// the intersection of the apparent discs. Occluded flux = the fully covered core (closed form)
// plus the ring lo = |s - a| < r < hi = min(1, s + a) where circles about the Sun's centre cross
// the occluder's edge:  integral I(r) 2 r theta(r) dr,  theta = half the covered arc.
// With r = lo + d, d = w sin^2(phi/2) (w = hi - lo), the square-root ends of theta and of the limb
// darkening become smooth in phi and 16 Gauss-Legendre points leave a quadrature error below
// 2e-8 (double; tests/test_eclipse_shadow.cpp). Float care, all in terms of d (no r - a, no
// 1 - r computed from r): theta comes from the half-angle form
//   tan^2(theta/2) = (a - r + s)(a + r - s) / ((r + s - a)(r + s + a)),
// whose four factors are sums of non-negative terms (s <= a: 2s - d, 2 lo + d, d, 2a + d;
// s > a: 2a - d, d, 2 lo + d, 2s + d), and 1 - r = (1 - hi) + w cos^2(phi/2) for the limb. So
// nearly equal discs at s -> 0 and huge occluders (a = 100, where r^2 - a^2 + s^2 would cancel)
// keep float precision: |error| < 3e-7 everywhere in the C++ build (float rounding of
// 1 - occluded / total); on a GPU the built-in atan's own error adds to it (llvmpipe's, ~3e-6
// absolute, gives up to ~1.1e-6).
float eclipse_visible_exact(float a, float s, float u) {
    float outer = 1.0 + a;  // rounded to float before comparing: C++ would compare in double
    if (s >= outer) {
        return 1.0;
    }
    float total = eclipse_disc_flux(1.0, u);
    float occluded = eclipse_disc_flux(clamp(a - s, 0.0, 1.0), u);
    float lo = abs(s - a);
    float hi = min(1.0, s + a);
    if (hi > lo && s > 0.0) {
        float w = hi - lo;
        float rim = 1.0 - hi;
        bool inside = s <= a;  // the Sun's centre is behind the occluder
        float ring = 0.0;
        for (int i = 0; i < 8; ++i) {
            vec3 node = eclipse_ring_node(i);
            for (int k = 0; k < 2; ++k) {
                float d = w * (k == 0 ? node.x : node.y);
                float one_minus_r = rim + w * (k == 0 ? node.y : node.x);
                float r = lo + d;
                float sin2 = inside ? (2.0 * s - d) * (2.0 * lo + d) : (2.0 * a - d) * d;
                float cos2 = inside ? d * (2.0 * a + d) : (2.0 * lo + d) * (2.0 * s + d);
                float theta = 2.0 * atan(sqrt(max(sin2, 0.0)), sqrt(max(cos2, 0.0)));
                float mu = sqrt(max(one_minus_r * (1.0 + r), 0.0));
                float intensity = 1.0 - u * (1.0 - mu);
                ring += node.z * intensity * r * theta;
            }
        }
        occluded += 2.0 * w * ring;
    }
    return clamp(1.0 - occluded / total, 0.0, 1.0);
}

// Fast mode (Ekelin & Fernqvist 2009, section 3.3.2, in angular terms): the visible fraction falls linearly
// across the penumbra from first contact (s = 1 + a) to the umbra/antumbra edge (s = |1 - a|),
// whose corner is rounded by a Butterworth factor of order n with its cut-off at that edge;
// inside, a uniform (not limb-darkened) disc: 0 in the umbra, 1 - a^2 in the antumbra.
// The Butterworth factor is divided by its value at first contact, so the shadow ends at exactly
// 1 there: undivided it is only 1 - 1 / (1 + ((1 + a) / (a - 1))^(2n)) at s = 1 + a, a step of
// 1.2 % at first contact for a = 3.7 (Earth from the Moon) and of 46 % for a = 100 (n = 4).
float eclipse_visible_fast(float a, float s, float n) {
    float outer = 1.0 + a;
    if (s >= outer) {
        return 1.0;
    }
    float inner = abs(1.0 - a);
    float deepest = a >= 1.0 ? 0.0 : 1.0 - a * a;
    float linear = clamp((s - inner) / (outer - inner), 0.0, 1.0);
    float edge = 1.0;
    if (inner > 0.0) {
        float e = 2.0 * n;
        float at_s = 1.0 - 1.0 / (1.0 + pow(max(s, 0.0) / inner, e));
        float at_outer = 1.0 - 1.0 / (1.0 + pow(outer / inner, e));
        edge = at_s / at_outer;
    }
    return deepest + (1.0 - deepest) * linear * edge;
}

// Lookup-table mode: a 2D table of the exact visible fraction (for one limb-darkening u), read
// bilinearly through texel centres. Texel (i, j) sits at x = i / (w - 1), y = j / (h - 1) of
//   x = 1/2 + (1/2) (A + K) / A * t / (|t| + K),  t = clamp(log2 a, -A, A)
//       (A = ECLIPSE_LUT_A_LOG2_MAX = -ECLIPSE_LUT_A_LOG2_MIN, K = ECLIPSE_LUT_A_KNEE: columns
//       packed around a = 1, where the Sun-Moon ratios 0.9 .. 1.1 lie, about 7x denser than
//       uniform in log2 a, and sparse towards a = 2^-6 and 2^6, where little changes with a);
//   y = Y s / inner                                inside the inner contact, s < inner = |1 - a|
//       (the antumbra, whose limb-darkened value changes with s; 0 throughout an umbra);
//   y = Y + (1 - Y) (s - inner) / (2 min(1, a))    across the penumbra, up to first contact
//       (Y = ECLIPSE_LUT_INNER_ROWS).
// With w odd a column lies on a = 1; with (h - 1) Y an integer a row lies on the inner contact.
// Beyond first contact the value is exactly 1; beyond 2^+-6 the column of the nearest end is
// used (with y still exact for the real a). eclipse_lut_parameters inverts the mapping: the
// table builder (common/eclipse/eclipse_reference.hpp) fills texel (i, j) with the reference at
// eclipse_lut_parameters(vec2(i / (w - 1), j / (h - 1))).
const float ECLIPSE_LUT_A_LOG2_MIN = -6.0;
const float ECLIPSE_LUT_A_LOG2_MAX = 6.0;
const float ECLIPSE_LUT_A_KNEE = 1.0;
const float ECLIPSE_LUT_INNER_ROWS = 0.125;

vec2 eclipse_lut_coordinates(float a, float s, vec2 size) {
    float t = clamp(log2(max(a, 1e-30)), ECLIPSE_LUT_A_LOG2_MIN, ECLIPSE_LUT_A_LOG2_MAX);
    float x = 0.5 + 0.5 * (ECLIPSE_LUT_A_LOG2_MAX + ECLIPSE_LUT_A_KNEE) / ECLIPSE_LUT_A_LOG2_MAX * t /
                        (abs(t) + ECLIPSE_LUT_A_KNEE);
    float inner = abs(1.0 - a);
    float y = s < inner ? ECLIPSE_LUT_INNER_ROWS * s / inner
                        : ECLIPSE_LUT_INNER_ROWS + (1.0 - ECLIPSE_LUT_INNER_ROWS) * (s - inner) / (2.0 * min(1.0, a));
    return (clamp(vec2(x, y), 0.0, 1.0) * (size - 1.0) + 0.5) / size;
}

// The (a, s) of the table point (x, y) in [0, 1]^2: the inverse of eclipse_lut_coordinates
// without its texel-centre step.
vec2 eclipse_lut_parameters(vec2 xy) {
    float q = (2.0 * xy.x - 1.0) * ECLIPSE_LUT_A_LOG2_MAX / (ECLIPSE_LUT_A_LOG2_MAX + ECLIPSE_LUT_A_KNEE);
    float t = ECLIPSE_LUT_A_KNEE * q / (1.0 - abs(q));
    float a = pow(2.0, t);
    float inner = abs(1.0 - a);
    float s = xy.y < ECLIPSE_LUT_INNER_ROWS
                  ? inner * xy.y / ECLIPSE_LUT_INNER_ROWS
                  : inner + 2.0 * min(1.0, a) * (xy.y - ECLIPSE_LUT_INNER_ROWS) / (1.0 - ECLIPSE_LUT_INNER_ROWS);
    return vec2(a, s);
}

float eclipse_visible_lut(sampler2D lut, vec2 size, float a, float s) {
    float outer = 1.0 + a;
    if (s >= outer) {
        return 1.0;
    }
    return clamp(textureLod(lut, eclipse_lut_coordinates(a, s, size), 0.0).r, 0.0, 1.0);
}

// Illustrative mode: 0 umbra, 1 antumbra, 2 penumbra, 3 outside every shadow.
int eclipse_region(float a, float s) {
    float outer = 1.0 + a;  // contacts rounded to float before comparing, as on the GPU
    float inner = abs(1.0 - a);
    if (s >= outer) {
        return 3;
    }
    if (s > inner) {
        return 2;
    }
    return a >= 1.0 ? 0 : 1;
}

// Uniform tints, the illustrative mode of Ekelin & Fernqvist 2009 (section 3.3.2, Figure 4.9): umbra
// red, antumbra blue, penumbra yellow; the surface keeps full sunlight times the tint, so the whole
// penumbra shows.
vec3 eclipse_region_tint(int region) {
    if (region == 0) {
        return vec3(0.85, 0.12, 0.10);
    }
    if (region == 1) {
        return vec3(0.20, 0.40, 0.95);
    }
    if (region == 2) {
        return vec3(1.00, 0.85, 0.30);
    }
    return vec3(1.0);
}

// The visible fraction in a numeric mode (exact, fast, lut); illustrative counts as exact here.
float eclipse_visible(int mode, float a, float s, float limb_u, float butterworth_order, sampler2D lut, vec2 lut_size) {
    if (mode == ECLIPSE_MODE_FAST) {
        return eclipse_visible_fast(a, s, butterworth_order);
    }
    if (mode == ECLIPSE_MODE_LUT) {
        return eclipse_visible_lut(lut, lut_size, a, s);
    }
    return eclipse_visible_exact(a, s, limb_u);
}
