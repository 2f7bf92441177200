// The frame barrier's rules, driven with explicit times.
#include <gtest/gtest.h>

#include "frame_barrier.hpp"

using namespace cupola;
using namespace std::chrono_literals;
using Clock = FrameBarrier::Clock;

TEST(FrameBarrier, WaitsForEveryLiveChannel) {
    FrameBarrier b({0, 1, 2}, 500ms);
    const auto t0 = Clock::time_point{} + 1h;
    for (int c : {0, 1, 2}) EXPECT_TRUE(b.on_alive(c, t0));
    b.start_frame(0, t0);
    EXPECT_EQ(b.pending().size(), 3u);
    EXPECT_TRUE(b.on_report(0, 0, t0 + 10ms));
    EXPECT_FALSE(b.on_report(1, 7, t0 + 10ms));  // another frame's report does not count
    EXPECT_TRUE(b.on_report(1, 0, t0 + 20ms));
    EXPECT_FALSE(b.complete());
    EXPECT_TRUE(b.on_report(2, 0, t0 + 30ms));
    EXPECT_TRUE(b.complete());
    b.start_frame(1, t0 + 40ms);
    EXPECT_FALSE(b.complete());
}

TEST(FrameBarrier, SilentChannelIsDroppedAndTheOthersGoOn) {
    FrameBarrier b({0, 1}, 500ms);
    const auto t0 = Clock::time_point{} + 1h;
    b.on_alive(0, t0);
    b.on_alive(1, t0);
    b.start_frame(5, t0);
    b.on_report(0, 5, t0 + 5ms);
    EXPECT_TRUE(b.expire(t0 + 499ms).empty());
    EXPECT_EQ(b.next_deadline(), t0 + 500ms);
    auto dropped = b.expire(t0 + 500ms);
    ASSERT_EQ(dropped, std::vector<int>{1});
    EXPECT_EQ(b.state(1), ChannelState::Dropped);
    EXPECT_TRUE(b.complete());
    EXPECT_EQ(b.live_count(), 1);
    // Next frames do not wait for it.
    b.start_frame(6, t0 + 600ms);
    b.on_report(0, 6, t0 + 610ms);
    EXPECT_TRUE(b.complete());
}

TEST(FrameBarrier, DroppedChannelRejoinsAndIsExpectedForTheCurrentFrame) {
    FrameBarrier b({0, 1}, 100ms);
    const auto t0 = Clock::time_point{} + 1h;
    b.on_alive(0, t0);
    b.on_alive(1, t0);
    b.start_frame(1, t0);
    b.on_report(0, 1, t0);
    b.expire(t0 + 200ms);
    ASSERT_EQ(b.state(1), ChannelState::Dropped);
    b.start_frame(2, t0 + 300ms);
    EXPECT_TRUE(b.on_alive(1, t0 + 310ms));   // hello from the restarted slave
    EXPECT_FALSE(b.on_alive(1, t0 + 320ms));  // already live: not a second rejoin
    auto p = b.pending();
    EXPECT_NE(std::find(p.begin(), p.end(), 1), p.end());
    b.on_report(0, 2, t0 + 330ms);
    EXPECT_FALSE(b.complete());
    EXPECT_TRUE(b.on_report(1, 2, t0 + 340ms));
    EXPECT_TRUE(b.complete());
}

TEST(FrameBarrier, UnknownChannelsAreIgnored) {
    FrameBarrier b({0}, 100ms);
    const auto t0 = Clock::time_point{} + 1h;
    EXPECT_FALSE(b.on_alive(9, t0));
    EXPECT_FALSE(b.on_report(9, 0, t0));
    EXPECT_FALSE(b.known(9));
    EXPECT_EQ(b.live_count(), 0);
    b.start_frame(0, t0);
    EXPECT_TRUE(b.complete());  // nobody live: nothing to wait for
}

// A channel's first frame after it was first seen, or after its process restarted, compiles its
// shaders: it has the longer first timeout; from its first report on, the usual one.
TEST(FrameBarrier, AChannelsFirstFrameHasTheLongerTimeout) {
    FrameBarrier b({0, 1}, 100ms, 1000ms);
    const auto t0 = Clock::time_point{} + 1h;
    b.on_alive(0, t0);
    b.on_alive(1, t0);
    b.start_frame(0, t0);
    b.on_report(0, 0, t0 + 50ms);
    EXPECT_TRUE(b.expire(t0 + 999ms).empty());  // channel 1 is still in its first frame
    EXPECT_EQ(b.next_deadline(), t0 + 1000ms);
    b.on_report(1, 0, t0 + 999ms);
    b.start_frame(1, t0 + 1s);
    b.on_report(0, 1, t0 + 1s + 10ms);
    EXPECT_EQ(b.next_deadline(), t0 + 1100ms);  // it has reported once: the usual timeout
    EXPECT_EQ(b.expire(t0 + 1100ms), std::vector<int>{1});
    // A new process for channel 1: its first frame again.
    b.on_restart(1, t0 + 1200ms);
    b.start_frame(2, t0 + 1200ms);
    b.on_report(0, 2, t0 + 1210ms);
    EXPECT_TRUE(b.expire(t0 + 2199ms).empty());
    EXPECT_EQ(b.expire(t0 + 2200ms), std::vector<int>{1});
    // Never shorter than the usual timeout.
    FrameBarrier short_first({0}, 100ms, 10ms);
    short_first.on_alive(0, t0);
    short_first.start_frame(0, t0);
    EXPECT_TRUE(short_first.expire(t0 + 99ms).empty());
    EXPECT_EQ(short_first.expire(t0 + 100ms), std::vector<int>{0});
}
