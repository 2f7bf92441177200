// The A.R.T. DTrack2 ASCII datagrams a CAVE's tracker sends (common/tracking/dtrack_packet): what is
// read from them, and the errors that name the line, its kind and what was wrong.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "tracking/dtrack_packet.hpp"

using namespace cupola;

namespace {

// The manual's example datagram: frame 21753, one of two calibrated bodies tracked.
const std::string kExample =
    "fr 21753\r\n"
    "ts 39596.024831\r\n"
    "6dcal 2\r\n"
    "6d 1 [0 1.000][326.848 -187.216 109.503 -160.4704 -3.6963 -7.0913][-0.940508 -0.339238 0.019025 "
    "0.333599 -0.932296 -0.139910 0.065200 -0.124843 0.990032]\r\n";

// The error a datagram gives (empty when it parses).
std::string error_of(const std::string& text) {
    try {
        parse_dtrack_packet(text);
    } catch (const DtrackError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(DtrackPacket, TheManualsExampleIsReadWithItsMatrixColumnByColumn) {
    const DtrackPacket p = parse_dtrack_packet(kExample);
    ASSERT_TRUE(p.frame.has_value());
    EXPECT_EQ(*p.frame, 21753u);
    EXPECT_DOUBLE_EQ(p.timestamp_s.value_or(0.0), 39596.024831);
    EXPECT_EQ(p.calibrated_bodies.value_or(-1), 2);
    ASSERT_EQ(p.bodies.size(), 1u);
    const DtrackBody& b = p.bodies[0];
    EXPECT_EQ(b.id, 0);
    EXPECT_DOUBLE_EQ(b.quality, 1.0);
    EXPECT_DOUBLE_EQ(b.position_mm.x, 326.848);
    EXPECT_DOUBLE_EQ(b.position_mm.y, -187.216);
    EXPECT_DOUBLE_EQ(b.position_mm.z, 109.503);
    // b0 b1 b2 is the first column: the body's x axis in the tracker's frame.
    EXPECT_DOUBLE_EQ(b.rotation[0][0], -0.940508);
    EXPECT_DOUBLE_EQ(b.rotation[0][1], -0.339238);
    EXPECT_DOUBLE_EQ(b.rotation[0][2], 0.019025);
    EXPECT_DOUBLE_EQ(b.rotation[1][0], 0.333599);
    EXPECT_DOUBLE_EQ(b.rotation[2][2], 0.990032);
    EXPECT_EQ(find_dtrack_body(p, 0), &p.bodies[0]);
    EXPECT_EQ(find_dtrack_body(p, 1), nullptr);
}

TEST(DtrackPacket, SeveralBodiesOtherKindsAndBareNewlines) {
    const DtrackPacket p = parse_dtrack_packet(
        "fr 8\n\n6d 2 [0 0.950][0 1700 0 0 0 0][1 0 0 0 1 0 0 0 1] [2 1.000][-500.5 1200 300 0 0 90]"
        "[0 1 0 -1 0 0 0 0 1]\n3d 1 [1 1.000][1 2 3]\ngl 0\n");
    ASSERT_EQ(p.bodies.size(), 2u);
    EXPECT_EQ(p.bodies[1].id, 2);
    EXPECT_DOUBLE_EQ(p.bodies[1].position_mm.x, -500.5);
    EXPECT_EQ(p.skipped_lines, 2);
    EXPECT_FALSE(p.timestamp_s.has_value());
    EXPECT_TRUE(parse_dtrack_packet("fr 9\r\n6d 0\r\n").bodies.empty());
}

TEST(DtrackPacket, BadDatagramsAreRefusedNamingTheLineAndWhatWasWrong) {
    const std::string rot = "[1 0 0 0 1 0 0 0 1]";
    EXPECT_EQ(error_of(""), "the datagram is empty");
    EXPECT_NE(error_of(std::string(70000, 'a')).find("70000 bytes"), std::string::npos);
    EXPECT_NE(error_of("6d 0\r\n").find("line 1 ('6d'): a DTrack2 datagram starts with its frame counter"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\nfr 2\r\n").find("line 2 ('fr'): the datagram has two lines"), std::string::npos);
    EXPECT_NE(error_of("fr x1\r\n").find("line 1 ('fr'): the frame counter: 'x1' is not a finite number"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1.5\r\n").find("the frame counter must be a whole number"), std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 2 [0 1][1 2 3 0 0 0]" + rot + "\r\n").find("line 2 ('6d'): expected '['"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 1 [0 1][1 2 0 0 0]" + rot + "\r\n").find("has 5 values, not 6"), std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 1 [0 1][nan 2 3 0 0 0]" + rot + "\r\n").find("'nan' is not a finite number"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 1 [0 1][1 2 3 0 0 0][2 0 0 0 1 0 0 0 1]\r\n").find("not a rotation"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 1 [0 1][1 2 3 0 0 0][-1 0 0 0 1 0 0 0 1]\r\n").find("determinant -1"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 2 [3 1][1 2 3 0 0 0]" + rot + "[3 1][1 2 3 0 0 0]" + rot + "\r\n")
                  .find("body 3 is given twice"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 1 [0 1][1 2 3 0 0 0]" + rot + " tail\r\n").find("unexpected text"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n\x01\x02garbage\r\n").find("line 2: the line does not start with a DTrack2 kind"),
              std::string::npos);
    EXPECT_NE(error_of("fr 1\r\n6d 300\r\n").find("the count of bodies must be a whole number from 0 to 256"),
              std::string::npos);
}

// Random bytes, and the example with random bytes changed: a packet or a DtrackError, nothing else
// (cupola-fuzz-dtrack explores further).
TEST(DtrackPacket, MangledDatagramsGiveAPacketOrItsErrorOnly) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> byte(0, 255);
    int refused = 0;
    for (int i = 0; i < 2000; ++i) {
        std::string text = kExample;
        if (i % 2) {
            text.assign(static_cast<size_t>(byte(rng)) + 1, ' ');
            for (char& c : text) c = static_cast<char>(byte(rng));
        } else {
            text[static_cast<size_t>(rng() % text.size())] = static_cast<char>(byte(rng));
        }
        try {
            const DtrackPacket p = parse_dtrack_packet(text);
            EXPECT_TRUE(p.frame.has_value());
        } catch (const DtrackError&) {
            ++refused;
        }
    }
    EXPECT_GT(refused, 1000);
}
