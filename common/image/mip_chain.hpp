#pragma once
// The mipmap chain of a linear float image (RGB maps, one-channel glyph coverage), built on the
// CPU with an area-weighted box filter (each texel of a level is the mean of the part of the level
// above that it covers, fractions of texels weighted by their overlap, so odd sizes lose no light).
//
// Why not glGenerateMipmap: for the RGB16F body maps Mesa's llvmpipe takes a software path that
// spent 190 ms on the 2048x1024 Earth, a fifth of a restarted slave's start-up; the chain here
// costs about 10 ms, and every driver of a cluster gets the same levels. The same holds for an
// R8 glyph atlas (about 100 ms in glGenerateTextureMipmap for 2048x400).
#include <vector>

namespace cupola {

struct MipLevel {
    int width = 0, height = 0, channels = 3;
    std::vector<float> texels;  // width*height*channels, row 0 first
};

// Levels 1.. of an image whose level 0 is (width, height, texels) with 1..4 interleaved channels:
// each max(1, n / 2) of the one before, down to 1x1. Empty when the image is 1x1. Throws
// std::invalid_argument when texels' size is not width*height*channels, or a size or the channel
// count is out of range.
std::vector<MipLevel> box_filter_mip_chain(int width, int height, const std::vector<float>& texels, int channels = 3);

}  // namespace cupola
