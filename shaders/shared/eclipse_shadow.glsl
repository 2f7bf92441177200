// Eclipse shadows of spherical casters (shared by GLSL and C++). Everything is in angular terms,
// normalised by the Sun's apparent radius: a = occluder radius / Sun radius (the occluder's
// apparent disc), s = centre separation / Sun radius. Contacts are at s = 1 + a (first/last)
// and s = |1 - a| (second/third); s < a - 1 is totality (umbra), s < 1 - a annularity
// (antumbra, a point beyond the umbra apex). Every function returns the visible fraction of the
// Sun's light in [0, 1] and never increases as the discs close (s decreasing).

// The apparent discs of the Sun and one caster seen from a point; to_sun and to_caster run from
// the point to the centres (any one length unit), radii in the same unit. A caster behind the
// point or beyond the Sun cannot occlude: s is set past first contact. Angles use asin of
// ratios and the chord 2 asin(|u1 - u2| / 2), never acos of a dot product (exact for the
// 0.25-degree discs of the Sun and Moon in float).
EclipseDiscs eclipse_discs(vec3 to_sun, float sun_radius, vec3 to_caster, float caster_radius) {
    EclipseDiscs d;
    float ds = length(to_sun);
    float dc = length(to_caster);
    d.sun_radius = asin(clamp(sun_radius / ds, 0.0, 1.0));
    float rc = asin(clamp(caster_radius / max(dc, caster_radius), 0.0, 1.0));
    d.ratio = rc / d.sun_radius;
    vec3 us = to_sun / ds;
    vec3 uc = to_caster / max(dc, 1e-30);
    float sep = 2.0 * asin(clamp(0.5 * length(us - uc), 0.0, 1.0));
    d.separation = sep / d.sun_radius;
    if (dc - caster_radius >= ds || dot(us, uc) <= 0.0) {
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

// Exact mode: visible fraction of the limb-darkened Sun behind an occluder disc (a, s), from
// the intersection of the apparent discs. Occluded flux = the fully covered core (closed form)
// plus the ring of radii where circles about the Sun's centre cross the occluder's edge:
//   integral I(r) 2 r theta(r) dr,  cos theta = ((r - a)(r + a) + s^2) / (2 r s),
// with r = lo + (hi - lo)(1 - cos phi) / 2: the square-root ends of theta and of the limb
// darkening become smooth in phi, so 16 Gauss-Legendre points reach float precision.
// (r - a)(r + a) is formed before adding s^2, which avoids the cancellation of nearly equal
// discs at s -> 0.
float eclipse_visible_exact(float a, float s, float u) {
    if (s >= 1.0 + a) {
        return 1.0;
    }
    float total = eclipse_disc_flux(1.0, u);
    float occluded = eclipse_disc_flux(clamp(a - s, 0.0, 1.0), u);
    float lo = abs(s - a);
    float hi = min(1.0, s + a);
    if (hi > lo && s > 0.0) {
        float half_phi = 0.5 * CUPOLA_PI;
        float ring = 0.0;
        for (int i = 0; i < 8; ++i) {
            vec2 nw = eclipse_gauss_legendre16(i);
            for (int k = 0; k < 2; ++k) {
                float phi = half_phi * (1.0 + (k == 0 ? -nw.x : nw.x));
                float r = lo + (hi - lo) * 0.5 * (1.0 - cos(phi));
                float dr_dphi = (hi - lo) * 0.5 * sin(phi);
                float c = ((r - a) * (r + a) + s * s) / max(2.0 * r * s, 1e-30);
                float theta = acos(clamp(c, -1.0, 1.0));
                float intensity = 1.0 - u * (1.0 - sqrt(max(1.0 - r * r, 0.0)));
                ring += nw.y * intensity * 2.0 * r * theta * dr_dphi;
            }
        }
        occluded += ring * half_phi;
    }
    return clamp(1.0 - occluded / total, 0.0, 1.0);
}

// Fast mode (seed 000, section 3.3.2, in angular terms): the visible fraction falls linearly
// across the penumbra from first contact (s = 1 + a) to the umbra/antumbra edge (s = |1 - a|),
// whose corner is rounded by a Butterworth factor of order n with its cut-off at that edge;
// inside, a uniform (not limb-darkened) disc: 0 in the umbra, 1 - a^2 in the antumbra.
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
        edge = 1.0 - 1.0 / (1.0 + pow(max(s, 0.0) / inner, e));
    }
    return deepest + (1.0 - deepest) * linear * edge;
}

// Lookup-table mode: table texel (i, j) holds the exact visible fraction at
//   a = 2^(A_LOG2_MIN + (A_LOG2_MAX - A_LOG2_MIN) i / (w - 1)),
//   s = |1 - a| + 2 min(1, a) j / (h - 1)          (second contact .. first contact),
// sampled bilinearly through texel centres; outside the contacts the value is exact (1 beyond
// first contact, the table's j = 0 row inside the inner contact).
const float ECLIPSE_LUT_A_LOG2_MIN = -6.0;
const float ECLIPSE_LUT_A_LOG2_MAX = 6.0;

vec2 eclipse_lut_coordinates(float a, float s, vec2 size) {
    float x = clamp((log2(max(a, 1e-30)) - ECLIPSE_LUT_A_LOG2_MIN) / (ECLIPSE_LUT_A_LOG2_MAX - ECLIPSE_LUT_A_LOG2_MIN), 0.0,
                    1.0);
    float inner = abs(1.0 - a);
    float y = clamp((s - inner) / (2.0 * min(1.0, a)), 0.0, 1.0);
    return (vec2(x, y) * (size - 1.0) + 0.5) / size;
}

float eclipse_visible_lut(sampler2D lut, vec2 size, float a, float s) {
    if (s >= 1.0 + a) {
        return 1.0;
    }
    return clamp(textureLod(lut, eclipse_lut_coordinates(a, s, size), 0.0).r, 0.0, 1.0);
}

// Illustrative mode: 0 umbra, 1 antumbra, 2 penumbra, 3 outside every shadow.
int eclipse_region(float a, float s) {
    if (s >= 1.0 + a) {
        return 3;
    }
    if (s > abs(1.0 - a)) {
        return 2;
    }
    return a >= 1.0 ? 0 : 1;
}

// Uniform tints of seed 000 Figure 4.9 (umbra red, antumbra blue, penumbra yellow): the surface
// keeps full sunlight times the tint, so the whole penumbra shows.
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
