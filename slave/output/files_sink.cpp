#include "output/files_sink.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace cupola {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }
}  // namespace

// Two reads per frame at most (the projector's linear EXR and its encoded PNG).
FilesSink::FilesSink(std::string dir, std::vector<std::string> formats, size_t frames_in_flight)
    : formats_(formats),
      writer_(std::move(dir), std::move(formats)),
      reads_(2 * std::max<size_t>(1, frames_in_flight)),
      max_frames_(std::max<size_t>(1, frames_in_flight)) {}

FilesSink::~FilesSink() { settle(); }

bool FilesSink::wants(const std::string& format) const {
    return std::find(formats_.begin(), formats_.end(), format) != formats_.end();
}

void FilesSink::take(const ProjectorFrame& frame) {
    const auto t0 = Clock::now();
    Pending p;
    p.meta = frame.meta();
    p.exposure = frame.exposure();
    p.warped = frame.warped();
    p.linear = !p.warped || wants("exr");
    p.encoded = p.warped && wants("png");
    const size_t reads = (p.linear ? 1 : 0) + (p.encoded ? 1 : 0);
    while ((reads_.free_slots() < reads || pending_.size() >= max_frames_) && !pending_.empty()) deliver_oldest();
    if (!p.warped) {
        p.width = frame.channel_width();
        p.height = frame.channel_height();
        reads_.start(frame.channel_texture(), p.width, p.height, PixelFormat::RgbaFloat);
    } else {
        p.width = frame.width();
        p.height = frame.height();
        if (p.linear) reads_.start(frame.linear_texture(), p.width, p.height, PixelFormat::RgbaFloat);
        if (p.encoded) reads_.start(frame.encoded_texture(), p.width, p.height, PixelFormat::RgbaBytes);
    }
    pending_.push_back(std::move(p));
    last_wait_ms_ = ms_since(t0);
}

void FilesSink::submit(const Pending& p) {
    Image linear;
    EncodedImage encoded;
    if (p.linear) {
        linear.width = p.width;
        linear.height = p.height;
        reads_.collect(linear.rgba);
    }
    if (p.encoded) {
        encoded.width = p.width;
        encoded.height = p.height;
        reads_.collect(encoded.rgba);
    }
    if (p.warped)
        writer_.submit_projected(std::move(linear), std::move(encoded), p.meta, p.exposure);
    else
        writer_.submit(std::move(linear), p.meta, p.exposure);
}

void FilesSink::deliver_oldest() {
    Pending p = std::move(pending_.front());
    pending_.pop_front();
    const size_t before = reads_.pending();
    try {
        submit(p);
    } catch (const std::exception& e) {
        ++failed_reads_;
        spdlog::error("frame {} of channel {} was not written: its read-back failed: {}", p.meta.frame,
                      p.meta.channel_name, e.what());
        // Drop what is left of this frame's reads, so that the next frame's are next.
        const size_t mine = (p.linear ? 1 : 0) + (p.encoded ? 1 : 0);
        while (reads_.pending() > before - mine) reads_.discard_oldest();
    }
}

double FilesSink::settle() {
    const auto t0 = Clock::now();
    while (!pending_.empty()) deliver_oldest();
    writer_.flush();
    return ms_since(t0);
}

uint64_t FilesSink::finish() {
    settle();
    return writer_.failed() + failed_reads_;
}

}  // namespace cupola
