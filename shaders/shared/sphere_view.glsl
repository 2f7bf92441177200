// View rays and analytic spheres (shared by GLSL and C++; angle_between_units is star_psf.glsl's).

// Unit view direction, in the channel frame (+X right, +Y up, -Z forward), through the point
// `frag` (window pixels, origin at the BOTTOM-left, like gl_FragCoord) of a size.x x size.y
// framebuffer whose frustum has the tangents (left, right, down, up) of its half-angles.
vec3 channel_ray(vec2 frag, vec2 size, vec4 tangents) {
    float x = -tangents.x + frag.x / size.x * (tangents.x + tangents.y);
    float y = -tangents.z + frag.y / size.y * (tangents.z + tangents.w);
    return normalize(vec3(x, y, -1.0));
}

// Where the view ray v (unit, from the camera) meets a sphere whose centre lies in the unit
// direction c_hat and whose angular radius alpha is given as sin_alpha = R / d.
// Returns (n, mu): n = unit outward surface normal at the first hit, mu = cos(angle between n
// and the direction back to the camera), with mu < 0 when the ray misses.
// Everything is in directions and ratios, never in positions: exact for any distance in float
// (the angle uses the chord, accurate for tiny angles; the CPU supplies c_hat and sin_alpha
// computed in double).
vec4 sphere_hit(vec3 v, vec3 c_hat, float sin_alpha) {
    float theta = angle_between_units(v, c_hat);
    if (theta >= 1.5707963) {
        return vec4(0.0, 0.0, 0.0, -1.0);
    }
    float rho = sin(theta) / sin_alpha;  // distance of the ray from the centre, in radii
    if (rho >= 1.0) {
        return vec4(0.0, 0.0, 0.0, -1.0);
    }
    float mu = sqrt(1.0 - rho * rho);
    vec3 perp = c_hat - v * cos(theta);  // from the ray toward the centre, length sin(theta)
    float plen = length(perp);
    vec3 n = -v * mu;
    if (plen > 1e-12) {
        n = n - perp * (rho / plen);
    }
    return vec4(normalize(n), mu);
}

// The view ray's distance from the sphere's centre in radii (sin(theta) / sin_alpha, as sphere_hit
// has it; 2 when the centre is behind): 1 on the limb. Its change across a pixel gives the limb's
// coverage of that pixel (body.frag).
float sphere_limb_rho(vec3 v, vec3 c_hat, float sin_alpha) {
    float theta = angle_between_units(v, c_hat);
    if (theta >= 1.5707963) return 2.0;
    return sin(theta) / sin_alpha;
}

// Distance from the camera to the hit found by sphere_hit (mu = its .w), from dist_m =
// (d, R, d - R, d + R) computed in double on the CPU (d = camera-centre distance, R = radius):
// t = (d - R)(d + R) / (d cos(theta) + R mu), the near root of the ray-sphere equation written
// without cancellation, so a surface a few metres away keeps its precision. 0 for a camera inside.
float sphere_hit_distance(vec3 v, vec3 c_hat, float mu, vec4 dist_m) {
    if (dist_m.z <= 0.0) return 0.0;
    float den = max(dist_m.x * dot(v, c_hat) + dist_m.y * mu, 1e-30);
    return min(dist_m.z * (dist_m.w / den), 1e30);
}

// Window depth of a camera distance, logarithmic from 1 m to 2^96 m (float keeps relative
// distances to ~1e-5 over the whole range). The bodies write it so that the glare probe's
// depth test orders them by true distance: their billboards all sit at the same scaled
// distance, so the rasterised depth means nothing.
float log_depth(float distance_m) {
    return clamp(log2(max(distance_m, 1.0)) / 96.0, 0.0, 1.0);
}

// Texture coordinates of an equirectangular body map (row 0 = north, lon = atan(y, x) in the body
// frame, north = +Z) at the unit surface normal n (channel frame): body.frag draws with it, and
// the atmosphere's look-up when it relights a surface that no body pass drew.
vec2 body_map_uv(mat3 channel_to_body, vec3 n) {
    vec3 nb = channel_to_body * n;
    float lon = atan(nb.y, nb.x);
    float lat = asin(clamp(nb.z, -1.0, 1.0));
    return vec2(0.5 + lon / (2.0 * CUPOLA_PI), 0.5 - lat / CUPOLA_PI);
}
