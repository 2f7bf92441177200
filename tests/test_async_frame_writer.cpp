// The slave's background frame writer: every submitted frame reaches the disk in order, the
// queue stays bounded, and a failed write is counted, never silent.
#include <gtest/gtest.h>

#include <filesystem>

#include "async_frame_writer.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {
Image small_image(float v) {
    Image img;
    img.width = img.height = 16;
    img.rgba.assign(16 * 16 * 4, v);
    return img;
}
}  // namespace

TEST(AsyncFrameWriter, EveryFrameReachesTheDisk) {
    const std::string dir = test::scratch_dir("async_writer");
    {
        AsyncFrameWriter w(dir, {"png", "exr"}, 1);
        for (uint64_t f = 0; f < 6; ++f) {
            FrameMetadata m;
            m.channel_id = 2;
            m.frame = f;
            m.snapshot_hash = "00112233445566" + std::to_string(10 + f);
            w.submit(small_image(0.1f * f), m, 1.0);
        }
        w.flush();
        EXPECT_EQ(w.written(), 6u);
        EXPECT_EQ(w.failed(), 0u);
        EXPECT_EQ(w.written_frames(), (std::vector<uint64_t>{0, 1, 2, 3, 4, 5}));  // in the order queued
    }
    for (uint64_t f = 0; f < 6; ++f) {
        FrameMetadata m;
        const Image img = read_image(dir + "/" + frame_file_name(f, "exr"), &m);
        EXPECT_EQ(m.frame, f);
        EXPECT_NEAR(img.pixel(3, 3)[0], 0.1f * f, 1e-3f);
        EXPECT_TRUE(std::filesystem::exists(dir + "/" + frame_file_name(f, "png")));
    }
}

TEST(AsyncFrameWriter, DestructorWritesWhatIsQueued) {
    const std::string dir = test::scratch_dir("async_writer_destructor");
    {
        AsyncFrameWriter w(dir, {"png"}, 3);
        for (uint64_t f = 0; f < 3; ++f) {
            FrameMetadata m;
            m.frame = f;
            w.submit(small_image(0.5f), m, 1.0);
        }
    }
    for (uint64_t f = 0; f < 3; ++f) EXPECT_TRUE(std::filesystem::exists(dir + "/" + frame_file_name(f, "png")));
}

TEST(AsyncFrameWriter, FailedWritesAreCounted) {
    const std::string dir = test::scratch_dir("async_writer_fail");
    test::write_text(dir + "/not-a-folder", "x");  // a file where the folder should be
    AsyncFrameWriter w(dir + "/not-a-folder/sub", {"png"}, 1);
    FrameMetadata m;
    w.submit(small_image(0.5f), m, 1.0);
    w.flush();
    EXPECT_EQ(w.failed(), 1u);
    EXPECT_EQ(w.written(), 0u);
}
