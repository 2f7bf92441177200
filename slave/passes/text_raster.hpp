#pragma once
// A line of text rasterized on the CPU with FreeType (FreeType tutorial, steps 1 and 2:
// FT_Set_Pixel_Sizes, FT_Load_Char with FT_LOAD_RENDER, the glyph metrics in 26.6 fixed point;
// docs/REFERENCES.md): the glyphs' 8-bit coverage placed along one baseline, one glyph per UTF-8
// character. Done once at start-up (the alignment pattern's channel label,
// slave/passes/pattern_pass.hpp; the overlays' label atlas, slave/passes/overlay_pass.hpp).
#include <memory>
#include <string>
#include <vector>

namespace cupola {

// The DejaVu Sans face that Debian's fonts-dejavu-core installs (scripts/setup.sh).
inline constexpr const char* kDefaultFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct TextRaster {
    int width = 0;
    int height = 0;               // the face's line height at the pixel size (ascender - descender)
    std::vector<float> coverage;  // width x height, 0..1, row 0 at the top
    float at(int x, int y) const { return coverage[static_cast<size_t>(y) * width + x]; }
};

// A face opened once at one pixel size (the em height, 4..512), for rasterizing many texts: opening
// the face is most of the cost of a short text. Throws std::runtime_error naming the font file and
// FreeType's error when the face cannot be opened, std::invalid_argument for the size.
class TextFace {
public:
    TextFace(int pixel_size, const std::string& font_file = kDefaultFontFile);
    ~TextFace();
    TextFace(const TextFace&) = delete;
    TextFace& operator=(const TextFace&) = delete;
    // The text in UTF-8 (a byte that does not begin a well-formed sequence, and a control
    // character, is drawn as '?'; a character the font lacks as its missing-glyph box); throws
    // std::runtime_error when a glyph cannot be rendered.
    TextRaster raster(const std::string& text) const;

private:
    struct Handle;
    std::unique_ptr<Handle> h_;
    std::string font_file_;
};

// One text with a face of its own.
TextRaster rasterize_text(const std::string& text, int pixel_size, const std::string& font_file = kDefaultFontFile);

}  // namespace cupola
