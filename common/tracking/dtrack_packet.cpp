#include "tracking/dtrack_packet.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

namespace cupola {

namespace {
constexpr double kRotationTolerance = 1e-3;  // DTrack2 prints the matrix to 6 decimals
constexpr size_t kMaxKindLength = 16;

bool is_space(char c) { return c == ' ' || c == '\t'; }
bool is_kind_char(char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); }

// One line, read left to right; every error names the line and its kind.
class LineReader {
public:
    LineReader(std::string_view text, int number) : rest_(text), number_(number) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw DtrackError("line " + std::to_string(number_) + (kind_.empty() ? "" : " ('" + kind_ + "')") + ": " +
                          what);
    }

    // The line's kind (its first word); "" for a blank line.
    const std::string& read_kind() {
        skip_spaces();
        size_t n = 0;
        while (n < rest_.size() && !is_space(rest_[n])) ++n;
        const std::string_view k = rest_.substr(0, n);
        if (k.size() > kMaxKindLength || !std::all_of(k.begin(), k.end(), is_kind_char))
            fail("the line does not start with a DTrack2 kind (lower-case letters and digits)");
        kind_ = std::string(k);
        rest_.remove_prefix(n);
        return kind_;
    }

    double number(const char* what) { return parse_number(next_token(), what); }

    int integer(const char* what, int lo, int hi) { return checked_integer(number(what), what, lo, hi); }

    int checked_integer(double v, const char* what, int lo, int hi) const {
        if (v != std::floor(v) || v < lo || v > hi)
            fail(std::string(what) + " must be a whole number from " + std::to_string(lo) + " to " +
                 std::to_string(hi));
        return static_cast<int>(v);
    }

    // A block "[v0 v1 ...]" of exactly `count` numbers.
    std::vector<double> block(const char* what, size_t count) {
        skip_spaces();
        if (rest_.empty() || rest_.front() != '[') fail(std::string("expected '[' opening ") + what);
        const size_t close = rest_.find(']');
        if (close == std::string_view::npos) fail(std::string(what) + " has no closing ']'");
        LineReader inner(rest_.substr(1, close - 1), number_);
        inner.kind_ = kind_;
        rest_.remove_prefix(close + 1);
        std::vector<double> v;
        while (!inner.at_end()) {
            if (v.size() == count) fail(std::string(what) + " has more than " + std::to_string(count) + " values");
            v.push_back(inner.number(what));
        }
        if (v.size() != count)
            fail(std::string(what) + " has " + std::to_string(v.size()) + " values, not " + std::to_string(count));
        return v;
    }

    bool at_end() {
        skip_spaces();
        return rest_.empty();
    }
    void expect_end() {
        if (!at_end()) fail("unexpected text after the line's values: '" + std::string(rest_.substr(0, 20)) + "'");
    }

private:
    void skip_spaces() {
        while (!rest_.empty() && is_space(rest_.front())) rest_.remove_prefix(1);
    }
    std::string_view next_token() {
        skip_spaces();
        size_t n = 0;
        while (n < rest_.size() && !is_space(rest_[n]) && rest_[n] != '[' && rest_[n] != ']') ++n;
        const std::string_view t = rest_.substr(0, n);
        rest_.remove_prefix(n);
        return t;
    }
    double parse_number(std::string_view t, const char* what) const {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
            fail(std::string(what) + ": '" + std::string(t.substr(0, 20)) + "' is not a finite number");
        return v;
    }

    std::string_view rest_;
    int number_;
    std::string kind_;
};

// The 3x3 matrix from its nine values column by column, checked to be a rotation.
glm::dmat3 rotation_of(const std::vector<double>& b, const LineReader& line) {
    const glm::dmat3 r(b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8]);  // glm is column-major too
    const glm::dmat3 rtr = glm::transpose(r) * r;
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(rtr[c][k] - (c == k ? 1.0 : 0.0)));
    if (worst > kRotationTolerance || glm::determinant(r) < 0.0)
        line.fail("the rotation matrix is not a rotation (R^T R differs from I by " + std::to_string(worst) +
                  ", determinant " + std::to_string(glm::determinant(r)) + ")");
    return r;
}

DtrackBody read_body(LineReader& line) {
    DtrackBody b;
    const std::vector<double> head = line.block("the body's [id quality]", 2);
    b.id = line.checked_integer(head[0], "the body's id", 0, 65535);
    b.quality = head[1];
    const std::vector<double> s = line.block("the body's [x y z eta theta phi]", 6);
    b.position_mm = glm::dvec3(s[0], s[1], s[2]);
    b.rotation = rotation_of(line.block("the body's rotation matrix", 9), line);
    return b;
}

void read_6d(LineReader& line, DtrackPacket& p) {
    const int n = line.integer("the count of bodies", 0, kDtrackMaxBodies);
    for (int i = 0; i < n; ++i) {
        DtrackBody b = read_body(line);
        if (find_dtrack_body(p, b.id)) line.fail("body " + std::to_string(b.id) + " is given twice");
        p.bodies.push_back(b);
    }
    line.expect_end();
}

// One line into the packet; `seen` marks the kinds read once per datagram.
void read_line(LineReader& line, const std::string& kind, DtrackPacket& p, std::string& seen) {
    if (kind == "fr" || kind == "ts" || kind == "6dcal" || kind == "6d") {
        const std::string mark = "|" + kind + "|";
        if (seen.find(mark) != std::string::npos) line.fail("the datagram has two lines of this kind");
        seen += mark;
    }
    if (kind == "fr") {
        p.frame = static_cast<uint64_t>(line.integer("the frame counter", 0, 2147483647));
        line.expect_end();
    } else if (kind == "ts") {
        p.timestamp_s = line.number("the timestamp");
        line.expect_end();
    } else if (kind == "6dcal") {
        p.calibrated_bodies = line.integer("the count of calibrated bodies", 0, kDtrackMaxBodies);
        line.expect_end();
    } else if (kind == "6d") {
        read_6d(line, p);
    } else {
        ++p.skipped_lines;
    }
}
}  // namespace

DtrackPacket parse_dtrack_packet(std::string_view text) {
    if (text.empty()) throw DtrackError("the datagram is empty");
    if (text.size() > kDtrackMaxPacketBytes)
        throw DtrackError("the datagram has " + std::to_string(text.size()) + " bytes (at most " +
                          std::to_string(kDtrackMaxPacketBytes) + ")");
    DtrackPacket p;
    std::string seen;
    int number = 0;
    while (!text.empty()) {
        const size_t eol = text.find('\n');
        std::string_view raw = text.substr(0, eol);
        text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
        if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
        LineReader line(raw, ++number);
        const std::string kind = line.read_kind();
        if (kind.empty()) continue;
        if (seen.empty() && kind != "fr") line.fail("a DTrack2 datagram starts with its frame counter ('fr')");
        read_line(line, kind, p, seen);
    }
    if (!p.frame) throw DtrackError("the datagram has no frame counter ('fr' line)");
    return p;
}

const DtrackBody* find_dtrack_body(const DtrackPacket& p, int id) {
    for (const DtrackBody& b : p.bodies)
        if (b.id == id) return &b;
    return nullptr;
}

}  // namespace cupola
