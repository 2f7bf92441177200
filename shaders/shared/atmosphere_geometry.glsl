// Ray-sphere geometry of the atmosphere in the (r, mu) parametrisation (shared by GLSL and C++):
// r = distance of the ray origin from the planet centre, mu = cosine of the ray's zenith angle.
// Discriminants are formed as (R - r)(R + r) + (r mu)^2: in float, R^2 - r^2 would lose the
// altitude of a camera near the ground (R^2 ~ 4e13 has an ulp of 4e6 m^2), and the ground/sky
// decision at mu_horizon +- 1e-6 with it.

float atm_discriminant(float r, float mu, float radius) {
    float rm = r * mu;
    return (radius - r) * (radius + r) + rm * rm;
}
// Distance to the far intersection with the top sphere (the exit, for an origin inside).
float atm_distance_to_top(AtmosphereParams a, float r, float mu) {
    float d = sqrt(max(atm_discriminant(r, mu, a.top_radius), 0.0));
    return max(-r * mu + d, 0.0);
}
// Distance to the near intersection with the ground sphere.
float atm_distance_to_ground(AtmosphereParams a, float r, float mu) {
    float d = sqrt(max(atm_discriminant(r, mu, a.bottom_radius), 0.0));
    return max(-r * mu - d, 0.0);
}
// True when the ray meets the ground: mu below the horizon's cosine -sqrt(1 - (bottom/r)^2).
// Callers decide this once per ray and pass the flag on, as Bruneton 2017 does: deciding again
// from rounded (r, mu) can flip the answer for rays near the horizon.
bool atm_ray_hits_ground(AtmosphereParams a, float r, float mu) {
    return mu < 0.0 && atm_discriminant(r, mu, a.bottom_radius) > 0.0 && r >= a.bottom_radius;
}
// Radius and zenith cosines a distance t along a ray that starts at (r, mu), with the Sun at
// zenith cosine mu_s and nu = cos(view, sun) (Bruneton's law of cosines form).
float atm_radius_at(float r, float mu, float t) {
    return sqrt(max(t * t + 2.0 * r * mu * t + r * r, 0.0));
}
float atm_mu_s_at(float r, float mu_s, float nu, float t, float r_t) {
    return clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
}

// Where a camera ray starts in the atmosphere (AtmosphereRayStart, atmosphere_types.glsl).
AtmosphereRayStart atm_ray_start(AtmosphereParams a, float d, vec3 v, vec3 c_hat, vec3 sun) {
    AtmosphereRayStart s;
    s.nu = dot(v, sun);
    s.offset = 0.0;
    s.valid = true;
    float r_cam = max(d, a.bottom_radius + 1.0);  // never below the ground
    if (r_cam <= a.top_radius) {
        s.r = r_cam;
        s.mu = -dot(v, c_hat);
        s.mu_s = -dot(sun, c_hat);
        return s;
    }
    float theta = 2.0 * asin(clamp(0.5 * length(v - c_hat), 0.0, 1.0));  // angle between v and c_hat
    float cos_t = cos(theta);
    float rho = r_cam * sin(theta);  // distance of the ray's line from the centre
    s.r = a.top_radius;
    if (cos_t <= 0.0 || rho >= a.top_radius) {
        s.mu = 0.0;
        s.mu_s = 0.0;
        s.valid = false;
        return s;
    }
    float half_chord = sqrt((a.top_radius - rho) * (a.top_radius + rho));
    s.offset = max(r_cam * cos_t - half_chord, 0.0);
    s.mu = -half_chord / a.top_radius;
    // Zenith at the entry: (rho u_perp - half_chord v) / top, u_perp = unit(v cos_t - c_hat)
    // points from the centre to the closest approach (undefined, and unneeded, when rho ~ 0).
    vec3 perp = v * cos_t - c_hat;
    float plen = length(perp);
    vec3 zenith = -v * half_chord;
    if (plen > 1e-12) zenith = zenith + perp * (rho / plen);
    s.mu_s = clamp(dot(normalize(zenith), sun), -1.0, 1.0);
    return s;
}
