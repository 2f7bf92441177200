#include "passes/body_texture.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

namespace cupola {

namespace {

float srgb_decode(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// srgb_decode for the few distinct values of an 8-bit image (k / 255): each computed once; a
// value that is not one of them is computed as it comes, so the result is srgb_decode's exactly.
class SrgbDecodeCache {
public:
    float operator()(float v) {
        const long k = std::lround(v * 255.0f);
        if (k < 0 || k > 255) return srgb_decode(v);
        Entry& e = entries_[static_cast<size_t>(k)];
        if (!e.valid || e.in != v) e = {true, v, srgb_decode(v)};
        return e.out;
    }

private:
    struct Entry {
        bool valid = false;
        float in = 0.0f, out = 0.0f;
    };
    std::array<Entry, 256> entries_{};
};

uint32_t hash32(uint32_t x) {  // lowbias32 (Chris Wellons)
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}
float hash01(uint32_t a, uint32_t b) {
    return static_cast<float>(hash32(a * 0x9E3779B9U ^ hash32(b)) >> 8) / 16777216.0f;
}

// Value noise on a periodic lattice (period px in x) so the longitude seam is continuous.
float value_noise(float x, float y, int period, uint32_t seed) {
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const float fx = x - x0, fy = y - y0;
    auto at = [&](int xi, int yi) {
        const int xm = ((xi % period) + period) % period;
        return hash01(seed, static_cast<uint32_t>(xm) * 73856093U ^ static_cast<uint32_t>(yi) * 19349663U);
    };
    const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    const float a = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * sx;
    const float b = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * sx;
    return a + (b - a) * sy;
}

// An 8-bit map (JPEG, most PNGs) read as bytes and decoded through a table of its 256 values:
// each is the float OIIO converts the byte to, decoded as srgb_decode does, so the result is the
// float path's bit for bit at a fraction of its cost (a 2048 x 1024 map is read at slave start-up).
BodyImage decode_8bit(OIIO::ImageInput& in, const std::string& texture) {
    const OIIO::ImageSpec& spec = in.spec();
    std::vector<uint8_t> bytes(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, bytes.data()))
        throw std::runtime_error("cannot read body texture \"" + texture + "\": " + in.geterror());
    std::array<float, 256> linear{};
    for (int k = 0; k < 256; ++k) {
        const uint8_t byte = static_cast<uint8_t>(k);
        float v = 0.0f;
        OIIO::convert_pixel_values(OIIO::TypeDesc::UINT8, &byte, OIIO::TypeDesc::FLOAT, &v, 1);
        linear[static_cast<size_t>(k)] = srgb_decode(v);
    }
    BodyImage img{spec.width, spec.height, std::vector<float>(static_cast<size_t>(spec.width) * spec.height * 3)};
    for (size_t i = 0; i < static_cast<size_t>(spec.width) * spec.height; ++i)
        for (int c = 0; c < 3; ++c)
            img.rgb[i * 3 + c] = linear[bytes[i * spec.nchannels + std::min(c, spec.nchannels - 1)]];
    return img;
}
}  // namespace

BodyImage generate_cratered_surface(int width, int height, unsigned seed) {
    BodyImage img{width, height, std::vector<float>(static_cast<size_t>(width) * height * 3)};
    constexpr double pi = std::numbers::pi;
    struct Crater {
        double x, y, z, radius, depth;
        double cos_reach;  // below this cosine a pixel is beyond 1.2 radii: outside floor and rim
    };
    std::vector<Crater> craters;
    for (uint32_t i = 0; i < 160; ++i) {
        const double z = 2.0 * hash01(seed + 1, i) - 1.0, lon = 2.0 * pi * hash01(seed + 2, i);
        const double r = std::sqrt(1.0 - z * z);
        const double size = 0.02 + 0.12 * std::pow(hash01(seed + 3, i), 3.0);  // radians, mostly small
        craters.push_back(
            {r * std::cos(lon), r * std::sin(lon), z, size, 0.5 + 0.5 * hash01(seed + 4, i), std::cos(1.2 * size)});
    }
    std::vector<const Crater*> near_row;  // the craters whose reach spans this row's latitude
    near_row.reserve(craters.size());
    for (int y = 0; y < height; ++y) {
        const double lat = pi / 2 - (y + 0.5) / height * pi;
        // A crater's reach is 1.2 radii of arc, and no arc is shorter than the difference in
        // latitude: a crater farther than that (with a margin for rounding) cannot touch the row.
        near_row.clear();
        for (const auto& c : craters)
            if (std::abs(lat - std::asin(std::clamp(c.z, -1.0, 1.0))) <= 1.2 * c.radius + 1e-6) near_row.push_back(&c);
        for (int x = 0; x < width; ++x) {
            const double lon = (x + 0.5) / width * 2 * pi - pi;
            const double px = std::cos(lat) * std::cos(lon), py = std::cos(lat) * std::sin(lon), pz = std::sin(lat);
            float v = 0.0f, amp = 0.5f;
            for (int o = 0; o < 4; ++o) {  // fbm, 4 octaves
                const int period = 8 << o;
                v += amp * value_noise(static_cast<float>(x) * period / width, static_cast<float>(y) * period / width,
                                       period, seed + 10 + o);
                amp *= 0.5f;
            }
            double shade = 0.25 + 0.2 * v;
            // Large dark "maria" from low-frequency noise.
            if (value_noise(static_cast<float>(x) * 4 / width, static_cast<float>(y) * 4 / width, 4, seed + 20) > 0.62f)
                shade *= 0.7;
            for (const Crater* cp : near_row) {
                const Crater& c = *cp;
                // Far from the crater (the floor and rim end at 1.15 radii): no acos, no effect.
                const double cos_angle = px * c.x + py * c.y + pz * c.z;
                if (cos_angle < c.cos_reach) continue;
                const double d = std::acos(std::clamp(cos_angle, -1.0, 1.0)) / c.radius;
                if (d < 0.85)
                    shade *= 1.0 - 0.25 * c.depth;  // floor
                else if (d < 1.15)
                    shade *= 1.0 + 0.35 * c.depth * (1.15 - d) / 0.3;  // bright rim
            }
            float* p = &img.rgb[(static_cast<size_t>(y) * width + x) * 3];
            p[0] = p[1] = p[2] = static_cast<float>(std::clamp(shade, 0.0, 1.0));
        }
    }
    return img;
}

BodyImage load_body_image(const std::string& texture) {
    const std::string prefix = "generated:";
    if (texture.rfind(prefix, 0) == 0) {
        const std::string name = texture.substr(prefix.size());
        uint32_t seed = 2166136261U;  // FNV-1a of the name: each generated body differs
        for (char ch : name) seed = (seed ^ static_cast<uint8_t>(ch)) * 16777619U;
        return generate_cratered_surface(512, 256, seed);
    }
    auto in = OIIO::ImageInput::open(texture);
    if (!in) throw std::runtime_error("cannot open body texture \"" + texture + "\": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 1)
        throw std::runtime_error("body texture \"" + texture + "\" has no pixels");
    if (spec.format == OIIO::TypeDesc::UINT8) return decode_8bit(*in, texture);
    std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
        throw std::runtime_error("cannot read body texture \"" + texture + "\": " + in->geterror());
    const bool is_float = spec.format.is_floating_point();  // EXR/HDR: already linear
    BodyImage img{spec.width, spec.height, std::vector<float>(static_cast<size_t>(spec.width) * spec.height * 3)};
    SrgbDecodeCache decode;
    for (size_t i = 0; i < static_cast<size_t>(spec.width) * spec.height; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = pixels[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
            img.rgb[i * 3 + c] = is_float ? v : decode(v);
        }
    return img;
}

glm::dvec3 body_map_mean_rgb(const BodyImage& image) {
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (int y = 0; y < image.height; ++y) {
        const double w = std::cos(((y + 0.5) / image.height - 0.5) * std::numbers::pi);
        glm::dvec3 row(0.0);
        for (int x = 0; x < image.width; ++x) {
            const float* p = &image.rgb[(static_cast<size_t>(y) * image.width + x) * 3];
            row += glm::dvec3(p[0], p[1], p[2]);
        }
        sum += w * row;
        weight += w * image.width;
    }
    return weight > 0.0 ? sum / weight : glm::dvec3(0.0);
}

}  // namespace cupola
