#pragma once
// Writes frame files on a thread of its own so that encoding (PNG deflate costs more than the
// render at 1024^2) overlaps the next frame's render. The queue is short: when it is full the
// render thread waits, so memory stays bounded and no frame is ever dropped.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "image/frame_image.hpp"

namespace cupola {

class AsyncFrameWriter {
public:
    AsyncFrameWriter(std::string dir, std::vector<std::string> formats, size_t max_queued = 2);
    ~AsyncFrameWriter();  // writes everything still queued, then stops
    AsyncFrameWriter(const AsyncFrameWriter&) = delete;
    AsyncFrameWriter& operator=(const AsyncFrameWriter&) = delete;

    // Queues a frame; blocks while the queue is full. Returns the milliseconds spent waiting.
    double submit(Image image, FrameMetadata meta, double exposure);
    // Queues a projector frame (slave/output/files_sink): the EXR from `linear` (already times the
    // exposure, so recorded with exposure 1), the PNG holding the `encoded` bytes as they are.
    // Either may be empty when its format is not written.
    double submit_projected(Image linear, EncodedImage encoded, FrameMetadata meta, double exposure);
    // Waits until every queued frame is on disk.
    void flush();

    uint64_t written() const;
    uint64_t failed() const;
    // The last frames written (at most kWrittenKept), oldest first, in the order their files
    // appeared: the order they were queued.
    std::vector<uint64_t> written_frames() const;
    static constexpr size_t kWrittenKept = 256;

private:
    struct Job {
        Image image;
        FrameMetadata meta;
        double exposure = 1.0;
        bool projected = false;
        EncodedImage encoded;
    };
    double queue(Job job);
    void write(const Job& job) const;
    void run();

    std::string dir_;
    std::vector<std::string> formats_;
    size_t max_queued_;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Job> queue_;
    bool busy_ = false;
    bool stopping_ = false;
    uint64_t written_ = 0;
    std::deque<uint64_t> written_frames_;
    uint64_t failed_ = 0;
    std::thread thread_;
};

}  // namespace cupola
