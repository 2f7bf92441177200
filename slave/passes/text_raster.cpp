#include "passes/text_raster.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <memory>
#include <cstdio>
#include <stdexcept>

namespace cupola {

namespace {

std::string freetype_failure(const std::string& what, const std::string& font_file, FT_Error error) {
    const char* text = FT_Error_String(error);
    return "text raster: " + what + " (font " + font_file +
           "): " + (text ? std::string(text) : "FreeType error " + std::to_string(error));
}

}  // namespace

// The library and the face, opened at a pixel size (released in reverse order).
struct TextFace::Handle {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
    Handle(const std::string& font_file, int pixel_size) {
        if (FT_Error e = FT_Init_FreeType(&library)) throw std::runtime_error(freetype_failure("init", font_file, e));
        if (FT_Error e = FT_New_Face(library, font_file.c_str(), 0, &face)) {
            FT_Done_FreeType(library);
            throw std::runtime_error(freetype_failure("cannot open the face", font_file, e));
        }
        if (FT_Error e = FT_Set_Pixel_Sizes(face, 0, static_cast<FT_UInt>(pixel_size))) {
            FT_Done_Face(face);
            FT_Done_FreeType(library);
            throw std::runtime_error(freetype_failure("cannot set the pixel size", font_file, e));
        }
    }
    ~Handle() {
        FT_Done_Face(face);
        FT_Done_FreeType(library);
    }
};

namespace {

// The length of the UTF-8 sequence a lead byte starts (0: not a lead byte).
int sequence_length(unsigned char b) {
    if (b < 0x80) return 1;
    if ((b & 0xE0) == 0xC0) return 2;
    if ((b & 0xF0) == 0xE0) return 3;
    if ((b & 0xF8) == 0xF0) return 4;
    return 0;
}

// One code point from text at i (advancing i): a well-formed, shortest UTF-8 sequence of a scalar
// value (RFC 3629 section 3), else '?' for its first byte. Control characters are '?' too.
char32_t next_code_point(const std::string& text, size_t& i) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const int n = sequence_length(lead);
    if (n == 0 || i + static_cast<size_t>(n) > text.size()) return ++i, U'?';
    char32_t cp = n == 1 ? lead : lead & (0x7F >> n);
    for (int k = 1; k < n; ++k) {
        const auto b = static_cast<unsigned char>(text[i + static_cast<size_t>(k)]);
        if ((b & 0xC0) != 0x80) return ++i, U'?';
        cp = (cp << 6) | (b & 0x3F);
    }
    static constexpr char32_t kShortest[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < kShortest[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return ++i, U'?';
    i += static_cast<size_t>(n);
    return cp < 0x20 || cp == 0x7F ? U'?' : cp;
}

void load_glyph(FT_Face face, char32_t cp, const std::string& font_file) {
    if (FT_Error e = FT_Load_Char(face, cp, FT_LOAD_RENDER)) {
        char name[16];
        std::snprintf(name, sizeof name, "U+%04X", static_cast<unsigned>(cp));
        throw std::runtime_error(freetype_failure(std::string("cannot render ") + name, font_file, e));
    }
}

// The glyph just loaded, its bitmap's top-left at (left, top) of the raster, clipped to it.
void blit_glyph(const FT_GlyphSlot g, int left, int top, TextRaster& out) {
    const FT_Bitmap& b = g->bitmap;
    for (unsigned row = 0; row < b.rows; ++row) {
        const int y = top + static_cast<int>(row);
        if (y < 0 || y >= out.height) continue;
        for (unsigned col = 0; col < b.width; ++col) {
            const int x = left + static_cast<int>(col);
            if (x < 0 || x >= out.width) continue;
            const float v = b.buffer[row * static_cast<unsigned>(b.pitch) + col] / 255.0f;
            float& dst = out.coverage[static_cast<size_t>(y) * out.width + x];
            dst = std::max(dst, v);
        }
    }
}

int checked_pixel_size(int pixel_size) {
    if (pixel_size < 4 || pixel_size > 512)
        throw std::invalid_argument("text raster: pixel size " + std::to_string(pixel_size) + " is not in 4..512");
    return pixel_size;
}
}  // namespace

TextFace::TextFace(int pixel_size, const std::string& font_file)
    : h_(std::make_unique<Handle>(font_file, checked_pixel_size(pixel_size))), font_file_(font_file) {}

TextFace::~TextFace() = default;

TextRaster rasterize_text(const std::string& text, int pixel_size, const std::string& font_file) {
    return TextFace(pixel_size, font_file).raster(text);
}

TextRaster TextFace::raster(const std::string& text) const {
    const std::string& font_file = font_file_;
    const Handle& h = *h_;
    const FT_Size_Metrics& m = h.face->size->metrics;
    const int ascender = static_cast<int>(m.ascender >> 6), descender = static_cast<int>(m.descender >> 6);
    std::vector<char32_t> code_points;
    for (size_t i = 0; i < text.size();) code_points.push_back(next_code_point(text, i));
    // The advance of every glyph gives the width; a margin of one pixel on each side.
    long pen_26_6 = 0;
    for (char32_t c : code_points) {
        load_glyph(h.face, c, font_file);
        pen_26_6 += h.face->glyph->advance.x;
    }
    TextRaster out;
    out.width = std::max(1, static_cast<int>(pen_26_6 >> 6) + 2);
    out.height = std::max(1, ascender - descender);
    out.coverage.assign(static_cast<size_t>(out.width) * out.height, 0.0f);
    long pen = 64;  // 26.6: one pixel of margin
    for (char32_t c : code_points) {
        load_glyph(h.face, c, font_file);
        const FT_GlyphSlot g = h.face->glyph;
        blit_glyph(g, static_cast<int>(pen >> 6) + g->bitmap_left, ascender - g->bitmap_top, out);
        pen += g->advance.x;
    }
    return out;
}

}  // namespace cupola
