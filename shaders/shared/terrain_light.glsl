// Light on the relief and its geomorph (shared by GLSL and C++; shaders/terrain.frag and .vert).
//
// A slope of unit normal n at a point whose local vertical is up receives the Sun's direct light
// by its own incidence, cos i = n.s, and the sky's by the part of the sky it sees: for an
// isotropic sky a plane tilted by theta sees (1 + cos theta) / 2 of it (the isotropic diffuse
// model of an inclined surface; Iqbal 1983, chapter 11). The relief's shadows on the sky light are
// left out. Both parts are per unit solar
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
