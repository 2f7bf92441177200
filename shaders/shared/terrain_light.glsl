// Light on the relief and its geomorph (shared by GLSL and C++; shaders/terrain.frag and .vert).
//
// A slope of unit normal n at a point whose local vertical is up receives the Sun's direct light
// by its own incidence, cos i = n.s, and the sky's by the part of the sky it sees: for an
// isotropic sky a plane tilted by theta sees (1 + cos theta) / 2 of it (the isotropic diffuse
// model of an inclined surface; Iqbal 1983, chapter 11). The relief's shadows on the Sun's light
// come from its horizon map (terrain_sun_visibility below); its shadows on the sky light are left
// out. Both parts are per unit solar
// irradiance, as the atmosphere's tables hold them (shared/atmosphere_tables.glsl): direct_t is
// the transmittance to the Sun at the point, sky_e the sky's irradiance on a horizontal plane.
vec3 terrain_illuminance(vec3 direct_t, vec3 sky_e, vec3 n, vec3 up, vec3 sun) {
    float cos_i = max(dot(n, sun), 0.0);
    float sky_view = 0.5 * (1.0 + clamp(dot(n, up), -1.0, 1.0));
    return direct_t * cos_i + sky_e * sky_view;
}

// The geomorph factor of a vertex distance_m from the camera in a tile that takes its parent's
// shape at morph_far_m (common/terrain/terrain_cut.hpp, CutTile::morph_far_m): 1 (its own shape)
// up to 0.7 of that distance, 0 (the parent's) from it on, a smoothstep between. A function of the
// camera and the vertex alone, so every channel of the cluster morphs a vertex alike; a tile drawn
// with morph_far_m <= 0 keeps its own shape.
float terrain_morph(float distance_m, float morph_far_m) {
    if (morph_far_m <= 0.0) {
        return 1.0;
    }
    return 1.0 - smoothstep(0.7 * morph_far_m, morph_far_m, distance_m);
}

// The local east at a point whose vertical is up (body frame, z the north pole): the horizon
// map's azimuth 0 (common/terrain/tile_horizon.hpp). At a pole, where east is undefined, the
// body's x axis stands in.
vec3 terrain_east(vec3 up) {
    vec3 e = cross(vec3(0.0, 0.0, 1.0), up);
    float len = length(e);
    return len > 1e-6 ? e / len : vec3(1.0, 0.0, 0.0);
}

// Horizon direction k (0..7) of a packed horizon map entry (common/terrain/tile_horizon.hpp,
// pack_horizon): two 12-bit values per component, the even direction in the high half; the sine
// of the horizon's elevation in [-1, 1].
float terrain_horizon_sine(vec4 map_entry, int k) {
    float v = map_entry[k / 2];
    float high = floor(v / 4096.0);
    float q = (k % 2 == 0) ? high : v - high * 4096.0;
    return q * (2.0 / 4095.0) - 1.0;
}

// The half-width of the shadow's edge, as a sine of elevation: the Sun's angular radius (4.65
// mrad) and about as much again for the horizon's interpolation between azimuths and vertices.
const float TERRAIN_SHADOW_EDGE = 0.01;

// How much of the Sun a point sees over the relief's horizon (0 in a mountain's shadow, 1 in the
// open): the horizon interpolated toward the Sun's azimuth (linear between the two neighbouring
// directions), and the Sun's elevation compared with it across a soft edge. up: the point's
// vertical; sun: unit, toward the Sun; both body frame. An entry of zeros is a horizon at
// -90 degrees everywhere: fully lit.
float terrain_sun_visibility(vec4 map_entry, vec3 up, vec3 sun) {
    vec3 east = terrain_east(up);  // perpendicular to up by construction
    vec3 north = cross(up, east);
    float azimuth_rad = atan(dot(sun, north), dot(sun, east));
    float f = azimuth_rad / (CUPOLA_PI / 4.0);
    if (f < 0.0) {
        f += 8.0;
    }
    float f0 = floor(f);
    int k0 = int(f0) % 8;
    int k1 = (k0 + 1) % 8;
    float horizon = mix(terrain_horizon_sine(map_entry, k0), terrain_horizon_sine(map_entry, k1), f - f0);
    return smoothstep(horizon - TERRAIN_SHADOW_EDGE, horizon + TERRAIN_SHADOW_EDGE, dot(sun, up));
}
