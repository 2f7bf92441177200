// Sunlight reaching a point past every caster that can shadow its receiver (shared by GLSL and
// C++). Positions are relative to the receiver's centre (see EclipseCasters). Casters multiply:
// exact for separate shadows, an approximation where two casters overlap the Sun at once.

// No casters: what a pass uses when nothing can shadow its receiver.
EclipseCasters eclipse_no_casters() {
    EclipseCasters e;
    e.count = 0;
    e.mode = ECLIPSE_MODE_EXACT;
    e.limb_u = 0.0;
    e.butterworth_order = 4.0;
    e.sun_position_m = vec3(0.0, 0.0, 1.0);
    e.sun_radius_m = 0.0;
    for (int i = 0; i < ECLIPSE_MAX_CASTERS; ++i) {
        e.caster_position_m[i] = vec3(0.0);
        e.caster_radius_m[i] = 0.0;
        e.umbra_light[i] = vec3(0.0);
    }
    return e;
}

// Light factor (rgb, 1 = full sunlight) at the point p_m. A caster leaves f of the Sun's light
// plus, over the part it hides, its umbra light (sunlight bent into the shadow by the caster's
// atmosphere: the red Moon of a lunar eclipse). Illustrative mode returns the region tint.
vec3 eclipse_light(EclipseCasters e, sampler2D lut, vec2 lut_size, vec3 p_m) {
    vec3 light = vec3(1.0);
    for (int i = 0; i < ECLIPSE_MAX_CASTERS; ++i) {
        if (i >= e.count) {
            break;
        }
        EclipseDiscs d = eclipse_discs(e.sun_position_m - p_m, e.sun_radius_m, e.caster_position_m[i] - p_m, e.caster_radius_m[i]);
        if (e.mode == ECLIPSE_MODE_ILLUSTRATIVE) {
            light = light * eclipse_region_tint(eclipse_region(d.ratio, d.separation));
        } else {
            float f = eclipse_visible(e.mode, d.ratio, d.separation, e.limb_u, e.butterworth_order, lut, lut_size);
            light = light * (vec3(f) + e.umbra_light[i] * (1.0 - f));
        }
    }
    return light;
}

EclipseRay eclipse_ray(EclipseCasters casters, vec2 lut_size, vec3 origin_m, vec3 dir) {
    EclipseRay r;
    r.casters = casters;
    r.lut_size = lut_size;
    r.origin_m = origin_m;
    r.dir = dir;
    return r;
}

// Light factor at distance t_m along the ray (1 when no caster is active).
vec3 eclipse_light_along(EclipseRay r, sampler2D lut, float t_m) {
    if (r.casters.count == 0) {
        return vec3(1.0);
    }
    return eclipse_light(r.casters, lut, r.lut_size, r.origin_m + r.dir * t_m);
}
