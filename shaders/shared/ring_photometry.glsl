// A planet's rings as a thin slab of particles in its equatorial plane (shared by GLSL and C++):
// where a ray meets the plane, how much light gets through, how bright the slab is from the lit
// face and from the unlit one, and how much of the Sun's disc the planet hides from a point of the
// rings. Lengths are in units of the planet's equatorial radius, relative to its centre.
//
// The slab in single scattering (Chandrasekhar 1960, chapter I, the diffuse reflection and
// transmission of a plane-parallel layer; the classical ring model Cuzzi et al. 1984 review in
// their section on ring photometry), with normal optical depth tau, mu0 = |cos| of the Sun's
// angle to the ring normal and mu = |cos| of the view ray's. The functions return the factor
// below; I/F is varpi0 P / 4 times it (the caller's, with varpi0 P the particles' single-
// scattering albedo times their phase function):
//   lit face:   I/F = mu0 / (mu + mu0) (1 - exp(-tau (1/mu + 1/mu0)))
//   unlit face: I/F = mu0 / (mu - mu0) (exp(-tau/mu) - exp(-tau/mu0))   (-> tau/mu0 exp(-tau/mu0)
//               at mu = mu0)
// The lit face of an opaque slab is Lommel-Seeliger's law; the unlit face glows where the rings
// are thin (the C ring, the Cassini division) and is dark where they are opaque (the B ring), as
// the Voyager and Cassini images from the unlit side show.

// The ray parameter t at which origin + t dir meets the plane through the centre with unit
// normal n; -1 when the ray runs parallel to it (a negative t is behind the origin).
float ring_plane_hit(vec3 origin, vec3 dir, vec3 n) {
    float dn = dot(dir, n);
    if (abs(dn) < 1e-12) {
        return -1.0;
    }
    return -dot(origin, n) / dn;
}

// The fraction of light that crosses the slab along a ray at |cos| mu to its normal.
float ring_transmission(float tau, float mu) {
    return exp(-tau / max(mu, 1e-6));
}

// The slab's I/F per unit varpi0 P / 4, seen from the lit face (same_side) or the unlit one.
float ring_reflectance(float tau, float mu0, float mu, bool same_side) {
    float m0 = max(mu0, 1e-6);
    float m = max(mu, 1e-6);
    if (same_side) {
        return m0 / (m + m0) * (1.0 - exp(-tau * (1.0 / m + 1.0 / m0)));
    }
    float d = m - m0;
    if (abs(d) < 1e-4 * m0) {
        return tau / m0 * exp(-tau / m0);
    }
    return m0 / d * (exp(-tau / m) - exp(-tau / m0));
}

// The fraction of a uniform disc left visible by a straight edge whose distance from the disc's
// centre is x disc radii, positive when the centre is on the visible side.
float disc_fraction_past_edge(float x) {
    float c = clamp(x, -1.0, 1.0);
    return clamp(0.5 + (c * sqrt(1.0 - c * c) + asin(c)) / 3.14159265358979, 0.0, 1.0);
}

// How much of the Sun's disc (angular radius sun_radius_rad) a point of the rings sees past its
// planet, in the planet's stretched frame (where the spheroid is the unit sphere): the point p and
// the direction to the Sun s (not unit after stretching). The planet's limb is taken as a straight
// edge across the Sun's disc, which it is to 1e-3 of the disc at Saturn (the Sun 0.03 degrees
// across, the planet 20 degrees and more from the rings).
float ring_sunlit_fraction(vec3 p, vec3 s, float sun_radius_rad) {
    float ss = dot(s, s);
    float t = -dot(p, s) / ss;  // the ray's closest approach to the centre
    if (t <= 0.0) {
        return 1.0;  // the Sun is on the point's side of the planet
    }
    float miss = length(p + t * s) - 1.0;  // > 0: the ray passes outside the planet
    float angle = miss / (t * sqrt(ss));     // the limb's angle from the Sun's centre, seen from p
    return disc_fraction_past_edge(angle / max(sun_radius_rad, 1e-9));
}
