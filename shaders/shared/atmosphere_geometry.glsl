// Ray-sphere geometry of the atmosphere in the (r, mu) parametrisation (shared by GLSL and C++):
// r_m = distance of the ray origin from the planet centre, mu = cosine of the ray's zenith angle.
// The intersections are those of ray_sphere.glsl (the reference integrator runs the same
// routines in double) with the atmosphere's two spheres; angles come from star_psf.glsl's
// angle_between_units.

// Distance to the far intersection with the top sphere (the exit, for an origin inside).
float atm_distance_to_top(AtmosphereParams a, float r_m, float mu) {
    return ray_sphere_far_m(r_m, mu, a.top_radius_m);
}
// Distance to the near intersection with the ground sphere.
float atm_distance_to_ground(AtmosphereParams a, float r_m, float mu) {
    return ray_sphere_near_m(r_m, mu, a.bottom_radius_m);
}
// True when the ray meets the ground (ray_hits_sphere).
bool atm_ray_hits_ground(AtmosphereParams a, float r_m, float mu) {
    return ray_hits_sphere(r_m, mu, a.bottom_radius_m);
}
// Radius and zenith cosines a distance t_m along a ray that starts at (r_m, mu), with the Sun at
// zenith cosine mu_s and nu = cos(view, sun) (Bruneton's law of cosines form).
float atm_radius_at(float r_m, float mu, float t_m) {
    return sqrt(max(t_m * t_m + 2.0 * r_m * mu * t_m + r_m * r_m, 0.0));
}
float atm_mu_s_at(float r_m, float mu_s, float nu, float t_m, float r_t_m) {
    return clamp((r_m * mu_s + t_m * nu) / r_t_m, -1.0, 1.0);
}

// Where a camera ray starts in the atmosphere (AtmosphereRayStart, atmosphere_types.glsl).
AtmosphereRayStart atm_ray_start(AtmosphereParams a, float d_m, vec3 v, vec3 c_hat, vec3 sun) {
    AtmosphereRayStart s;
    s.nu = dot(v, sun);
    s.offset_m = 0.0;
    s.valid = true;
    float r_cam = max(d_m, a.bottom_radius_m + 1.0);  // never below the ground
    if (r_cam <= a.top_radius_m) {
        s.r_m = r_cam;
        s.mu = -dot(v, c_hat);
        s.mu_s = -dot(sun, c_hat);
        return s;
    }
    float theta = angle_between_units(v, c_hat);
    float cos_t = cos(theta);
    float rho = r_cam * sin(theta);  // distance of the ray's line from the centre
    s.r_m = a.top_radius_m;
    if (cos_t <= 0.0 || rho >= a.top_radius_m) {
        s.mu = 0.0;
        s.mu_s = 0.0;
        s.valid = false;
        return s;
    }
    float half_chord = sqrt((a.top_radius_m - rho) * (a.top_radius_m + rho));
    s.offset_m = max(r_cam * cos_t - half_chord, 0.0);
    s.mu = -half_chord / a.top_radius_m;
    // Zenith at the entry: (rho u_perp - half_chord v) / top, u_perp = unit(v cos_t - c_hat)
    // points from the centre to the closest approach (undefined, and unneeded, when rho ~ 0).
    vec3 perp = v * cos_t - c_hat;
    float plen = length(perp);
    vec3 zenith = -v * half_chord;
    if (plen > 1e-12) zenith = zenith + perp * (rho / plen);
    s.mu_s = clamp(dot(normalize(zenith), sun), -1.0, 1.0);
    return s;
}
