// The alignment grid (docs/ALIGNMENT.md), shared by GLSL and C++ (common/shading/shared_shading.hpp):
// lines of azimuth and elevation in the dome frame (common/projection/dome_frame.hpp: apex +Y,
// front -Z, right +X), a function of the dome direction alone, so every channel that sees a
// direction draws the same line there. Azimuth 0 is the front, 90 deg the right; elevation 90
// deg the apex. Lines every 10 deg, every 5 deg within 20 deg of the springline; the springline
// and the meridians 0/90/180/270 are coloured and wider. A line has a constant angular width, but
// never less than 1.5 pixels, and is anti-aliased by its coverage of the pixel.

const float GRID_DEG = CUPOLA_PI / 180.0;
const float GRID_HALF_WIDTH_RAD = 0.15 * GRID_DEG;   // lines 0.3 deg wide (where pixels are finer)
const float GRID_FINE_BELOW_RAD = 20.0 * GRID_DEG;   // 5 deg spacing at |elevation| below this
const float GRID_MERIDIAN_TOP_RAD = 80.0 * GRID_DEG;  // minor meridians end here (they converge)

// (azimuth, elevation) in radians of a unit dome-frame direction; azimuth in (-pi, pi].
vec2 dome_azimuth_elevation(vec3 d) { return vec2(atan(d.x, -d.z), asin(clamp(d.y, -1.0, 1.0))); }

// Angular size of a pixel of a channel at the tangent-plane point xy (x right, y up, z = -1),
// for pixels tan_per_pixel wide in the tangent plane: the geometric mean of the radial
// (dr / (1 + r^2)) and tangential (dr / sqrt(1 + r^2)) extents.
float grid_pixel_rad(vec2 xy, float tan_per_pixel) { return tan_per_pixel / pow(1.0 + dot(xy, xy), 0.75); }

// Coverage (0..1) of a pixel of angular size pixel_rad whose centre lies distance_rad from the
// centre of a line of half width half_width_rad (a box filter across the line).
float grid_line_coverage(float distance_rad, float half_width_rad, float pixel_rad) {
    float h = max(half_width_rad, 0.75 * pixel_rad);
    return clamp((h + 0.5 * pixel_rad - distance_rad) / pixel_rad, 0.0, 1.0);
}

// Line spacing at an elevation: 5 deg near the springline, 10 deg above.
float grid_spacing_rad(float elevation_rad) { return abs(elevation_rad) < GRID_FINE_BELOW_RAD ? 5.0 * GRID_DEG : 10.0 * GRID_DEG; }

// Distance from x to the nearest multiple of step.
float grid_distance_to_multiple(float x, float step_size) { return abs(x - step_size * floor(x / step_size + 0.5)); }

// Angular distance of (az, el) from the meridian (half great circle) at azimuth az_line.
float grid_meridian_distance(float az, float el, float az_line) {
    return asin(clamp(cos(el) * abs(sin(az - az_line)), 0.0, 1.0));
}

// The grid's colour (linear, on black) at a unit dome-frame direction for pixels of angular size
// pixel_rad. The coloured lines are drawn over the grey ones, which leave them out.
vec3 alignment_grid(vec3 dome_dir, float pixel_rad) {
    vec2 ae = dome_azimuth_elevation(dome_dir);
    float az = ae.x;
    float el = ae.y;
    float spacing = grid_spacing_rad(el);
    float quarter = 0.5 * CUPOLA_PI;
    // Elevation circles (the springline apart): the distance along the meridian.
    float circle = 0.0;
    if (abs(el) > 0.5 * spacing) {
        circle = grid_line_coverage(grid_distance_to_multiple(el, spacing), GRID_HALF_WIDTH_RAD, pixel_rad);
    }
    // Minor meridians (the main ones apart), up to GRID_MERIDIAN_TOP_RAD.
    float az_line = spacing * floor(az / spacing + 0.5);
    float meridian = 0.0;
    if (el < GRID_MERIDIAN_TOP_RAD && grid_distance_to_multiple(az_line, quarter) > 0.5 * spacing) {
        meridian = grid_line_coverage(grid_meridian_distance(az, el, az_line), GRID_HALF_WIDTH_RAD, pixel_rad);
    }
    vec3 color = vec3(0.6, 0.6, 0.6) * max(circle, meridian);
    // The springline, wider and yellow.
    float spring = grid_line_coverage(abs(el), 2.0 * GRID_HALF_WIDTH_RAD, pixel_rad);
    color = mix(color, vec3(1.0, 0.85, 0.1), spring);
    // The main meridians to the apex: the front (azimuth 0) red, 90/180/270 green.
    float main_az = quarter * floor(az / quarter + 0.5);
    float main_line = grid_line_coverage(grid_meridian_distance(az, el, main_az), 2.0 * GRID_HALF_WIDTH_RAD, pixel_rad);
    vec3 main_color = abs(main_az) < 0.25 * quarter ? vec3(1.0, 0.15, 0.15) : vec3(0.15, 1.0, 0.3);
    return mix(color, main_color, main_line);
}
