// The viewer's head for VR walls and CAVEs: a DTrack2 stream, recorded by the test and sent over a
// real UDP socket, moves the head as it says (every axis' sign, millimetres to metres, both axes
// conventions); the tracker's fallback when it falls silent; the filters; the presenter's "head"
// command; garbage datagrams change nothing; the pose travels in the snapshot.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "control/control_command.hpp"
#include "net/udp_socket.hpp"
#include "tracking/dtrack_receiver.hpp"
#include "tracking/head_tracker.hpp"
#include "tracking/tracker_mounting.hpp"
#include "util/monotonic_clock.hpp"
#include "wire/snapshot.hpp"
#include "wire/byte_io.hpp"

using namespace cupola;

namespace {

constexpr uint64_t kMs = 1000000;  // ns

// One DTrack2 datagram with the head (body 0) at p_mm, unrotated unless told.
std::string dtrack_datagram(uint64_t frame, const glm::dvec3& p_mm, const std::string& rotation = "1 0 0 0 1 0 0 0 1") {
    char buf[256];
    std::snprintf(buf, sizeof buf, "fr %llu\r\n6dcal 1\r\n6d 1 [0 1.000][%.3f %.3f %.3f 0 0 0][%s]\r\n",
                  static_cast<unsigned long long>(frame), p_mm.x, p_mm.y, p_mm.z, rotation.c_str());
    return buf;
}

HeadPose tracked_at(const glm::dvec3& p) {
    HeadPose h;
    h.position_m = p;
    h.source = HeadSource::Tracked;
    return h;
}

// Sends a datagram to the receiver and reads until the tracker has counted it.
void deliver(UdpSocket& out, DtrackReceiver& rx, HeadTracker& tracker, const std::string& text) {
    const uint64_t before = tracker.counters().packets;
    out.send_to(make_address("127.0.0.1", rx.port()), reinterpret_cast<const uint8_t*>(text.data()), text.size());
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (tracker.counters().packets == before && std::chrono::steady_clock::now() < until) {
        rx.drain(tracker);
        if (tracker.counters().packets == before) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_GT(tracker.counters().packets, before) << "the datagram did not arrive";
}

}  // namespace

TEST(HeadTracking, TheTrackersMillimetresAndAxesBecomeTheRoomsMetres) {
    DtrackBody b;
    b.position_mm = glm::dvec3(100.0, 1700.0, -250.0);
    // y_up: the room's own axes, plus the tracker's origin in the room.
    HeadPose p = head_pose_from_dtrack(b, {TrackerAxes::YUp, glm::dvec3(0.0, 0.0, 1.0)});
    EXPECT_LT(glm::length(p.position_m - glm::dvec3(0.1, 1.7, 0.75)), 1e-12);
    EXPECT_EQ(p.source, HeadSource::Tracked);
    // z_up: x right, y to the front screen (the room's -z), z up.
    b.position_mm = glm::dvec3(100.0, 2000.0, 1700.0);
    p = head_pose_from_dtrack(b, {TrackerAxes::ZUp, glm::dvec3(0.0)});
    EXPECT_LT(glm::length(p.position_m - glm::dvec3(0.1, 1.7, -2.0)), 1e-12);
    // A head turned 90 degrees to its left about the tracker's up axis looks along the room's -x.
    b.rotation = glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, 1));  // about z_up
    p = head_pose_from_dtrack(b, {TrackerAxes::ZUp, glm::dvec3(0.0)});
    const glm::dvec3 looks = p.orientation * glm::dvec3(0.0, 0.0, -1.0);
    EXPECT_LT(glm::length(looks - glm::dvec3(-1.0, 0.0, 0.0)), 1e-9);
}

// A recorded stream: the head steps along +x, +y and +z and back, with garbage between the steps.
// Each step moves the pose by the step's millimetres as metres, with the step's sign; a garbage
// datagram is counted and changes nothing.
TEST(HeadTracking, ARecordedDtrackStreamOverUdpMovesTheHeadAsItSays) {
    HeadTrackingConfig cfg;
    cfg.source = TrackingSource::Dtrack;
    cfg.address = "127.0.0.1";
    cfg.port = 0;
    cfg.fresh_s = 10.0;
    cfg.timeout_s = 20.0;
    DtrackReceiver rx(cfg);
    HeadTracker tracker(cfg, glm::dvec3(0.0, 1.7, 0.0));
    UdpSocket out;
    const glm::dvec3 start_mm(0.0, 1700.0, 0.0);
    const glm::dvec3 steps_mm[] = {{250, 0, 0}, {-250, 0, 0}, {0, 120, 0}, {0, -120, 0}, {0, 0, 400}, {0, 0, -400}};
    uint64_t frame = 1;
    glm::dvec3 at_mm = start_mm;
    deliver(out, rx, tracker, dtrack_datagram(frame++, at_mm));
    for (const glm::dvec3& step : steps_mm) {
        const glm::dvec3 before = tracker.frame_pose(monotonic_ns()).pose.position_m;
        at_mm += step;
        deliver(out, rx, tracker, dtrack_datagram(frame++, at_mm));
        const FrameHeadPose now = tracker.frame_pose(monotonic_ns());
        EXPECT_EQ(now.pose.source, HeadSource::Tracked);
        EXPECT_LT(glm::length(now.pose.position_m - at_mm * 1e-3), 1e-9);
        for (int axis = 0; axis < 3; ++axis) {
            const double moved_m = now.pose.position_m[axis] - before[axis];
            if (step[axis] == 0.0)
                EXPECT_NEAR(moved_m, 0.0, 1e-12) << "axis " << axis;
            else
                EXPECT_EQ(moved_m > 0.0, step[axis] > 0.0) << "axis " << axis;
        }
        EXPECT_TRUE(now.new_sample_arrival_ns.has_value());
        deliver(out, rx, tracker, "fr 99\r\n6d 1 [0 1][nan 0 0 0 0 0][1 0 0 0 1 0 0 0 1]\r\n");
        deliver(out, rx, tracker, std::string("\x00\xff\x13garbage", 10));
        const FrameHeadPose after = tracker.frame_pose(monotonic_ns());
        EXPECT_EQ(after.pose.position_m, now.pose.position_m);
        EXPECT_FALSE(after.new_sample_arrival_ns.has_value());
    }
    EXPECT_EQ(tracker.counters().bad_packets, 12u);
    EXPECT_EQ(tracker.counters().samples, 7u);
    // A datagram that tracks only another body is counted, and changes nothing either.
    deliver(out, rx, tracker, "fr 100\r\n6d 1 [4 1][0 0 0 0 0 0][1 0 0 0 1 0 0 0 1]\r\n");
    EXPECT_EQ(tracker.counters().without_body, 1u);
    EXPECT_EQ(tracker.counters().samples, 7u);
}

// Fresh for 0.1 s, then held, then the default eye after the 2 s timeout, counted as one loss;
// the tracker coming back is counted as a recovery.
TEST(HeadTracking, ASilentTrackerIsHeldThenGivenUpForTheDefaultEye) {
    HeadTrackingConfig cfg;
    HeadTracker t(cfg, glm::dvec3(0.0, 1.7, 0.0));
    EXPECT_EQ(t.frame_pose(0).pose.source, HeadSource::Default);
    EXPECT_EQ(t.frame_pose(0).pose.position_m, glm::dvec3(0.0, 1.7, 0.0));
    const uint64_t t0 = 1000 * kMs;
    t.add_sample(tracked_at({0.5, 1.6, 0.2}), t0);
    EXPECT_EQ(t.frame_pose(t0 + 10 * kMs).pose.source, HeadSource::Tracked);
    const FrameHeadPose held = t.frame_pose(t0 + 500 * kMs);
    EXPECT_EQ(held.pose.source, HeadSource::Held);
    EXPECT_EQ(held.pose.position_m, glm::dvec3(0.5, 1.6, 0.2));
    EXPECT_EQ(t.frame_pose(t0 + 1990 * kMs).pose.source, HeadSource::Held);
    const FrameHeadPose lost = t.frame_pose(t0 + 2010 * kMs);
    EXPECT_EQ(lost.pose.source, HeadSource::Default);
    EXPECT_EQ(lost.pose.position_m, glm::dvec3(0.0, 1.7, 0.0));
    EXPECT_EQ(t.frame_pose(t0 + 3000 * kMs).pose.source, HeadSource::Default);
    EXPECT_EQ(t.counters().losses, 1u);
    t.add_sample(tracked_at({-0.5, 1.5, 0.0}), t0 + 4000 * kMs);
    EXPECT_EQ(t.frame_pose(t0 + 4001 * kMs).pose.position_m, glm::dvec3(-0.5, 1.5, 0.0));
    EXPECT_EQ(t.counters().recoveries, 1u);
    EXPECT_EQ(t.counters().held_frames, 2u);
    EXPECT_EQ(t.counters().default_frames, 4u);
    EXPECT_EQ(t.counters().tracked_frames, 2u);
}

TEST(HeadTracking, SmoothingLagsAndPredictionLeads) {
    HeadTrackingConfig cfg;
    cfg.filter = HeadFilter::Smooth;
    cfg.smoothing_s = 0.05;
    HeadTracker smooth(cfg, glm::dvec3(0.0));
    smooth.add_sample(tracked_at({0.0, 0.0, 0.0}), 0);
    smooth.add_sample(tracked_at({1.0, 0.0, 0.0}), 50 * kMs);  // one time constant later
    EXPECT_NEAR(smooth.frame_pose(50 * kMs).pose.position_m.x, 1.0 - std::exp(-1.0), 1e-9);

    cfg.filter = HeadFilter::Predict;
    cfg.prediction_s = 0.02;
    HeadTracker predict(cfg, glm::dvec3(0.0));
    predict.add_sample(tracked_at({0.0, 1.0, 0.0}), 0);
    predict.add_sample(tracked_at({0.01, 1.0, 0.0}), 10 * kMs);  // 1 m/s along x
    // The frame is built 5 ms after the sample: predicted to 5 + 20 ms past it.
    EXPECT_NEAR(predict.frame_pose(15 * kMs).pose.position_m.x, 0.01 + 0.025, 1e-9);
}

TEST(HeadTracking, ThePresentersHeadCommandOverridesTheTrackerUntilReleased) {
    const ControlCommand c = parse_control_line("head 0.5 1.6 -0.25 90 0 0");
    EXPECT_EQ(c.verb, ControlVerb::Head);
    ASSERT_TRUE(c.head.has_value());
    EXPECT_DOUBLE_EQ((*c.head)[2], -0.25);
    EXPECT_DOUBLE_EQ((*c.head)[3], 90.0);
    EXPECT_FALSE(parse_control_line("head release").head.has_value());
    EXPECT_THROW(parse_control_line("head 1 2"), ControlError);
    EXPECT_THROW(parse_control_line("head 1 2 x"), ControlError);
    EXPECT_THROW(parse_control_line("head 1 2 20000"), ControlError);

    HeadTracker t(HeadTrackingConfig{}, glm::dvec3(0.0, 1.7, 0.0));
    t.add_sample(tracked_at({0.1, 1.7, 0.0}), 0);
    HeadPose p;
    p.position_m = glm::dvec3(0.5, 1.6, -0.25);
    t.set_control_pose(p);
    EXPECT_EQ(t.frame_pose(1 * kMs).pose.source, HeadSource::Control);
    EXPECT_EQ(t.frame_pose(1 * kMs).pose.position_m, p.position_m);
    t.set_control_pose(std::nullopt);
    EXPECT_EQ(t.frame_pose(2 * kMs).pose.position_m, glm::dvec3(0.1, 1.7, 0.0));
}

TEST(HeadTracking, ThePoseTravelsInTheSnapshotAndABadOneIsRefused) {
    Snapshot s;
    s.head.position_m = glm::dvec3(0.25, 1.55, -0.4);
    s.head.orientation = glm::normalize(glm::dquat(0.9, 0.1, -0.3, 0.2));
    s.head.source = HeadSource::Held;
    std::vector<uint8_t> bytes = encode_snapshot(s);
    EXPECT_EQ(decode_snapshot(bytes.data(), bytes.size()), s);
    Snapshot moved = s;
    moved.head.position_m.x += 0.001;
    EXPECT_NE(snapshot_hash(encode_snapshot(moved)), snapshot_hash(bytes));
    // The head's source is the first of its 57 bytes at the end.
    bytes[bytes.size() - 57] = 9;
    try {
        decode_snapshot(bytes.data(), bytes.size());
        ADD_FAILURE() << "an unknown head source was accepted";
    } catch (const WireError& e) {
        EXPECT_NE(std::string(e.what()).find("head.source"), std::string::npos);
    }
}
