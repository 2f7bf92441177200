#include "async_frame_writer.hpp"

#include <spdlog/spdlog.h>

#include <chrono>

namespace cupola {

AsyncFrameWriter::AsyncFrameWriter(std::string dir, std::vector<std::string> formats, size_t max_queued)
    : dir_(std::move(dir)), formats_(std::move(formats)), max_queued_(std::max<size_t>(1, max_queued)) {
    thread_ = std::thread([this] { run(); });
}

AsyncFrameWriter::~AsyncFrameWriter() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

double AsyncFrameWriter::submit(Image image, FrameMetadata meta, double exposure) {
    Job job;
    job.image = std::move(image);
    job.meta = std::move(meta);
    job.exposure = exposure;
    return queue(std::move(job));
}

double AsyncFrameWriter::submit_projected(Image linear, EncodedImage encoded, FrameMetadata meta, double exposure) {
    Job job;
    job.image = std::move(linear);
    job.meta = std::move(meta);
    job.exposure = exposure;
    job.projected = true;
    job.encoded = std::move(encoded);
    return queue(std::move(job));
}

double AsyncFrameWriter::queue(Job job) {
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < max_queued_; });
    queue_.push_back(std::move(job));
    lock.unlock();
    changed_.notify_all();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void AsyncFrameWriter::flush() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.empty() && !busy_; });
}

uint64_t AsyncFrameWriter::written() const {
    std::lock_guard lock(mutex_);
    return written_;
}

std::vector<uint64_t> AsyncFrameWriter::written_frames() const {
    std::lock_guard lock(mutex_);
    return {written_frames_.begin(), written_frames_.end()};
}

uint64_t AsyncFrameWriter::failed() const {
    std::lock_guard lock(mutex_);
    return failed_;
}

void AsyncFrameWriter::write(const Job& job) const {
    if (!job.projected) {
        write_frame(dir_, job.image, job.meta, formats_, job.exposure);
        return;
    }
    for (const auto& f : formats_) {
        if (f == "exr") write_frame(dir_, job.image, job.meta, {"exr"}, 1.0);
        if (f == "png") write_encoded_png(dir_, job.encoded, job.meta, job.exposure);
    }
}

void AsyncFrameWriter::run() {
    for (;;) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
        if (queue_.empty()) return;  // stopping, and everything is written
        Job job = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        lock.unlock();
        changed_.notify_all();  // room in the queue
        bool ok = true;
        try {
            write(job);
        } catch (const std::exception& e) {
            ok = false;
            spdlog::error("frame {} of channel {} was not written: {}", job.meta.frame, job.meta.channel_name,
                          e.what());
        }
        lock.lock();
        busy_ = false;
        ++(ok ? written_ : failed_);
        if (ok) written_frames_.push_back(job.meta.frame);
        if (written_frames_.size() > kWrittenKept) written_frames_.pop_front();
        lock.unlock();
        changed_.notify_all();
    }
}

}  // namespace cupola
