// Where a direction falls on a map of the sky in galactic coordinates (shared by GLSL and C++),
// laid out as Milky Way panoramas are: galactic longitude 0 at the map's centre, increasing to the
// left (the sky seen from inside), latitude +latitude_extent on the top row (v = 0) and
// -latitude_extent on the bottom one (v = 1). g: unit, galactic frame (x toward l = 0, b = 0;
// z toward the north galactic pole). u wraps at l = 180 degrees; v outside [0, 1] is off the map.
vec2 galactic_map_uv(vec3 g, float latitude_extent_rad) {
    float l = atan(g.y, g.x);
    float b = asin(clamp(g.z, -1.0, 1.0));
    return vec2(fract(0.5 - l * 0.15915494), 0.5 - 0.5 * b / latitude_extent_rad);
}
