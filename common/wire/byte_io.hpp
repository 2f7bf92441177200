#pragma once
// Explicitly little-endian encoding of integers and IEEE-754 doubles/floats, independent of the
// host's byte order. ByteReader throws WireError naming the field on a short buffer.
#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace cupola {

class WireError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class ByteWriter {
public:
    explicit ByteWriter(std::vector<uint8_t>& out) : out_(out) {}
    void u8(uint8_t v) { out_.push_back(v); }
    void u16(uint16_t v) { put(v, 2); }
    void u32(uint32_t v) { put(v, 4); }
    void u64(uint64_t v) { put(v, 8); }
    void f32(float v) { u32(std::bit_cast<uint32_t>(v)); }
    void f64(double v) { u64(std::bit_cast<uint64_t>(v)); }
    void bytes(const uint8_t* p, size_t n) { out_.insert(out_.end(), p, p + n); }

private:
    void put(uint64_t v, int n) {
        for (int i = 0; i < n; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    std::vector<uint8_t>& out_;
};

class ByteReader {
public:
    ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    uint8_t u8(const char* field) { return static_cast<uint8_t>(get(1, field)); }
    uint16_t u16(const char* field) { return static_cast<uint16_t>(get(2, field)); }
    uint32_t u32(const char* field) { return static_cast<uint32_t>(get(4, field)); }
    uint64_t u64(const char* field) { return get(8, field); }
    float f32(const char* field) { return std::bit_cast<float>(u32(field)); }
    double f64(const char* field) { return std::bit_cast<double>(u64(field)); }
    size_t remaining() const { return size_ - pos_; }
    size_t position() const { return pos_; }

private:
    uint64_t get(int n, const char* field) {
        if (size_ - pos_ < static_cast<size_t>(n))
            throw WireError(std::string("truncated at field '") + field + "' (offset " + std::to_string(pos_) + ")");
        uint64_t v = 0;
        for (int i = 0; i < n; ++i) v |= static_cast<uint64_t>(data_[pos_ + i]) << (8 * i);
        pos_ += n;
        return v;
    }
    const uint8_t* data_;
    size_t size_;
    size_t pos_ = 0;
};

}  // namespace cupola
