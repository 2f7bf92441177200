#include "calibration/pfm_file.hpp"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "calibration/calibration_error.hpp"

namespace cupola {

namespace {

struct PfmHeader {
    int width = 0;
    int height = 0;
    int channels = 0;
    bool little_endian = true;
    size_t data_offset = 0;
};

// One whitespace-delimited token from `pos`; leading whitespace skipped, and exactly one
// whitespace character after it consumed (netpbm's rule for the last header field).
std::string next_token(const std::string& bytes, size_t& pos, const std::string& name, const char* field) {
    while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    const size_t start = pos;
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos])) && pos - start < 32) ++pos;
    if (start == pos || pos >= bytes.size())
        throw CalibrationError(name, field, "missing or truncated PFM header field");
    std::string token = bytes.substr(start, pos - start);
    ++pos;
    return token;
}

int parse_dimension(const std::string& token, const std::string& name, const char* field) {
    if (token.empty() || token.size() > 6)
        throw CalibrationError(name, field, "'" + token + "' is not a size 1..100000");
    for (char c : token)
        if (!std::isdigit(static_cast<unsigned char>(c)))
            throw CalibrationError(name, field, "'" + token + "' is not a size 1..100000");
    const int v = std::stoi(token);
    if (v < 1 || v > 100000) throw CalibrationError(name, field, "'" + token + "' is not a size 1..100000");
    return v;
}

PfmHeader parse_header(const std::string& bytes, const std::string& name) {
    PfmHeader h;
    if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f'))
        throw CalibrationError(name, "PFM magic", "not a PFM file (expected 'PF' or 'Pf')");
    h.channels = bytes[1] == 'F' ? 3 : 1;
    size_t pos = 2;
    if (pos >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[pos])))
        throw CalibrationError(name, "PFM magic", "no whitespace after the magic");
    h.width = parse_dimension(next_token(bytes, pos, name, "PFM width"), name, "PFM width");
    h.height = parse_dimension(next_token(bytes, pos, name, "PFM height"), name, "PFM height");
    const std::string scale_text = next_token(bytes, pos, name, "PFM scale");
    char* end = nullptr;
    const double scale = std::strtod(scale_text.c_str(), &end);
    if (end != scale_text.c_str() + scale_text.size() || !std::isfinite(scale) || scale == 0.0)
        throw CalibrationError(name, "PFM scale", "'" + scale_text + "' is not a non-zero number");
    h.little_endian = scale < 0.0;  // netpbm: negative scale = little-endian
    h.data_offset = pos;
    return h;
}

uint32_t byte_swap(uint32_t v) { return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24); }

bool host_little_endian() { return std::endian::native == std::endian::little; }

}  // namespace

PfmImage decode_pfm(const std::string& bytes, const std::string& name, PfmRows rows) {
    const PfmHeader h = parse_header(bytes, name);
    const size_t count = static_cast<size_t>(h.width) * h.height * h.channels;
    const size_t have = bytes.size() - h.data_offset;
    if (have < count * 4)
        throw CalibrationError(name, "PFM data",
                               std::to_string(h.width) + "x" + std::to_string(h.height) + "x" +
                                   std::to_string(h.channels) + " floats need " + std::to_string(count * 4) +
                                   " bytes, the file has " + std::to_string(have));
    PfmImage img{h.width, h.height, h.channels, std::vector<float>(count)};
    const bool swap = h.little_endian != host_little_endian();
    const size_t row_floats = static_cast<size_t>(h.width) * h.channels;
    for (int file_row = 0; file_row < h.height; ++file_row) {
        const int y = rows == PfmRows::bottom_first ? h.height - 1 - file_row : file_row;
        const char* src = bytes.data() + h.data_offset + file_row * row_floats * 4;
        for (size_t k = 0; k < row_floats; ++k) {
            uint32_t word;
            std::memcpy(&word, src + 4 * k, 4);
            if (swap) word = byte_swap(word);
            std::memcpy(&img.data[y * row_floats + k], &word, 4);
        }
    }
    return img;
}

PfmImage read_pfm_file(const std::string& path, PfmRows rows) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CalibrationError(path, "", "cannot open the PFM file");
    std::ostringstream s;
    s << in.rdbuf();
    return decode_pfm(s.str(), path, rows);
}

std::string encode_pfm(const PfmImage& image, PfmRows rows, PfmByteOrder order) {
    if ((image.channels != 1 && image.channels != 3) || image.width < 1 || image.height < 1 ||
        image.data.size() != static_cast<size_t>(image.width) * image.height * image.channels)
        throw CalibrationError("PFM image", "size", "inconsistent image to encode");
    const bool little = order == PfmByteOrder::little_endian;
    std::string out = std::string(image.channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(image.width) + " " +
                      std::to_string(image.height) + "\n" + (little ? "-1.0" : "1.0") + "\n";
    const size_t header = out.size();
    const size_t row_floats = static_cast<size_t>(image.width) * image.channels;
    out.resize(header + image.data.size() * 4);
    const bool swap = little != host_little_endian();
    for (int file_row = 0; file_row < image.height; ++file_row) {
        const int y = rows == PfmRows::bottom_first ? image.height - 1 - file_row : file_row;
        for (size_t k = 0; k < row_floats; ++k) {
            uint32_t word;
            std::memcpy(&word, &image.data[y * row_floats + k], 4);
            if (swap) word = byte_swap(word);
            std::memcpy(&out[header + (file_row * row_floats + k) * 4], &word, 4);
        }
    }
    return out;
}

void write_pfm_file(const std::string& path, const PfmImage& image, PfmRows rows, PfmByteOrder order) {
    const std::string bytes = encode_pfm(image, rows, order);
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw CalibrationError(path, "", "cannot write the PFM file");
}

}  // namespace cupola
