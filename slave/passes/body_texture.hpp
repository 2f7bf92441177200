#pragma once
// Surface images of bodies: equirectangular (longitude -180..180 left to right, north at the top),
// converted to linear RGB floats. "generated:<name>" textures are procedural and deterministic.
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace cupola {

struct BodyImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // width*height*3, linear, row 0 = north
};

// Loads an image file with OpenImageIO (8/16-bit files are decoded from sRGB) or makes a
// generated one. Throws std::runtime_error naming the path or the unknown generator.
BodyImage load_body_image(const std::string& texture);

// The map's mean linear colour over the sphere's area (each row weighted by the cosine of its
// latitude): what a Lambert sphere's disc-integrated light is proportional to.
glm::dvec3 body_map_mean_rgb(const BodyImage& image);

// A grey, cratered, moon-like surface from hashed noise; the same for the same seed.
BodyImage generate_cratered_surface(int width, int height, unsigned seed);

}  // namespace cupola
