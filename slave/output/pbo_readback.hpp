#pragma once
// Asynchronous read-back of textures to the CPU through a ring of pixel buffer objects. start()
// queues a glReadPixels of the texture into the next free buffer (GL_PIXEL_PACK_BUFFER bound: the
// call returns at once, the copy runs on the GPU after the draws before it) and a fence after it;
// collect() takes the oldest read, waits on its fence (normally signalled by then: a whole frame
// was drawn after it), maps the buffer and copies its rows out, top row first. Reads come out in
// the order they were started; a read that cannot be started because every buffer is in use is a
// logic error the caller avoids by collecting first (free_slots()). Needs a current GL 4.5
// context for its whole life; the buffers are allocated on first use and grow to the largest read.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace cupola {

// What one read copies out: RGBA 32-bit float (linear light, the range physical units need) or
// RGBA 8-bit (bytes already encoded for a display).
enum class PixelFormat { RgbaFloat, RgbaBytes };

size_t bytes_per_pixel(PixelFormat f);

class PboReadback {
public:
    explicit PboReadback(size_t slots);
    ~PboReadback();
    PboReadback(const PboReadback&) = delete;
    PboReadback& operator=(const PboReadback&) = delete;

    // Queues a read of level 0 of `texture` (GL name, width x height, GL row 0 at the bottom).
    // Throws std::logic_error when no slot is free, std::runtime_error on a GL error.
    void start(unsigned texture, int width, int height, PixelFormat format);
    // Copies the oldest read into `out` (resized to width x height x bytes_per_pixel), row 0 the
    // TOP row. Throws std::logic_error when nothing is pending, std::runtime_error when the GPU
    // does not finish the copy within a minute or the buffer cannot be mapped.
    void collect(std::vector<uint8_t>& out);
    void collect(std::vector<float>& out);

    // Forgets the oldest read without copying it (after a failed collect of a frame's other read).
    void discard_oldest();

    size_t pending() const { return pending_.size(); }
    size_t free_slots() const { return slots_.size() - pending_.size(); }
    uint64_t reads_started() const { return started_; }

private:
    struct Slot {
        unsigned buffer = 0;
        size_t capacity = 0;
        void* fence = nullptr;  // GLsync
        int width = 0, height = 0;
        PixelFormat format = PixelFormat::RgbaFloat;
    };
    // Waits for the oldest read and copies it, flipped, into dst (size bytes exactly).
    void copy_oldest(void* dst, size_t size);
    const Slot& oldest() const;

    std::vector<Slot> slots_;
    std::deque<size_t> pending_;  // slot indices, oldest first
    size_t next_ = 0;             // the slot the next start() uses
    unsigned read_fbo_ = 0;
    uint64_t started_ = 0;
};

}  // namespace cupola
