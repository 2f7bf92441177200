// Which channel owns a direction (shared by GLSL and C++). Projector channels overlap; a
// quantity measured per channel and summed over the cluster (the glare's visible solid angle)
// must count each direction once. The owner is the channel in which the direction lies most
// centrally: the smallest score below, the lowest channel index on a tie. Every channel
// evaluates the same scores from the same directions, so exactly one keeps each direction.

// max(|x|, |y|) of the direction's normalised device coordinates in a channel whose frustum
// has the tangents (left, right, down, up); v in that channel's frame (-Z forward). At most 1
// inside the frustum; a very large value behind the projector.
float channel_ndc_score(vec3 v, vec4 tangents) {
    if (v.z >= 0.0) {
        return 1.0e30;
    }
    float x = v.x / -v.z;
    float y = v.y / -v.z;
    float nx = (2.0 * x - (tangents.y - tangents.x)) / (tangents.x + tangents.y);
    float ny = (2.0 * y - (tangents.w - tangents.z)) / (tangents.z + tangents.w);
    return max(abs(nx), abs(ny));
}
