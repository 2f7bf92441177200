#include "output/pbo_readback.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include "gl/gl_api.hpp"

namespace cupola {

size_t bytes_per_pixel(PixelFormat f) { return f == PixelFormat::RgbaFloat ? 16 : 4; }

PboReadback::PboReadback(size_t slots) : slots_(slots) {
    if (slots == 0) throw std::invalid_argument("pbo read-back: a ring of 0 buffers");
    glCreateFramebuffers(1, &read_fbo_);
    for (Slot& s : slots_) glCreateBuffers(1, &s.buffer);
    gl::check("pbo read-back buffers");
}

PboReadback::~PboReadback() {
    for (Slot& s : slots_) {
        if (s.fence) glDeleteSync(static_cast<GLsync>(s.fence));
        glDeleteBuffers(1, &s.buffer);
    }
    glDeleteFramebuffers(1, &read_fbo_);
}

void PboReadback::start(unsigned texture, int width, int height, PixelFormat format) {
    if (free_slots() == 0)
        throw std::logic_error("pbo read-back: all " + std::to_string(slots_.size()) +
                               " buffers hold reads not yet collected");
    Slot& s = slots_[next_];
    const size_t size = static_cast<size_t>(width) * height * bytes_per_pixel(format);
    if (s.capacity < size) {
        glNamedBufferData(s.buffer, static_cast<GLsizeiptr>(size), nullptr, GL_STREAM_READ);
        s.capacity = size;
    }
    glNamedFramebufferTexture(read_fbo_, GL_COLOR_ATTACHMENT0, texture, 0);
    glNamedFramebufferReadBuffer(read_fbo_, GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo_);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, s.buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    const bool bytes = format == PixelFormat::RgbaBytes;
    glReadPixels(0, 0, width, height, GL_RGBA, bytes ? GL_UNSIGNED_BYTE : GL_FLOAT, nullptr);  // into the buffer
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    s.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();  // the read and the fence reach the GPU now, not at the next frame's first draw
    gl::check("pbo read-back start (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    s.width = width;
    s.height = height;
    s.format = format;
    pending_.push_back(next_);
    next_ = (next_ + 1) % slots_.size();
    ++started_;
}

const PboReadback::Slot& PboReadback::oldest() const {
    if (pending_.empty()) throw std::logic_error("pbo read-back: collect() with no read pending");
    return slots_[pending_.front()];
}

void PboReadback::copy_oldest(void* dst, size_t size) {
    Slot& s = slots_[pending_.front()];
    const GLenum waited = glClientWaitSync(static_cast<GLsync>(s.fence), GL_SYNC_FLUSH_COMMANDS_BIT, 60'000'000'000ull);
    glDeleteSync(static_cast<GLsync>(s.fence));
    s.fence = nullptr;
    pending_.pop_front();
    if (waited == GL_TIMEOUT_EXPIRED || waited == GL_WAIT_FAILED)
        throw std::runtime_error("pbo read-back: the GPU did not finish a " + std::to_string(s.width) + "x" +
                                 std::to_string(s.height) + " read within a minute");
    const auto* src =
        static_cast<const uint8_t*>(glMapNamedBufferRange(s.buffer, 0, static_cast<GLsizeiptr>(size), GL_MAP_READ_BIT));
    if (!src) throw std::runtime_error("pbo read-back: the pixel buffer could not be mapped");
    const size_t row = static_cast<size_t>(s.width) * bytes_per_pixel(s.format);
    auto* out = static_cast<uint8_t*>(dst);
    for (int y = 0; y < s.height; ++y)  // GL row 0 is the bottom one
        std::memcpy(out + static_cast<size_t>(y) * row, src + static_cast<size_t>(s.height - 1 - y) * row, row);
    glUnmapNamedBuffer(s.buffer);
    gl::check("pbo read-back collect");
}

void PboReadback::discard_oldest() {
    Slot& s = slots_[pending_.at(0)];
    glDeleteSync(static_cast<GLsync>(s.fence));
    s.fence = nullptr;
    pending_.pop_front();
}

void PboReadback::collect(std::vector<uint8_t>& out) {
    const Slot& s = oldest();
    if (s.format != PixelFormat::RgbaBytes) throw std::logic_error("pbo read-back: the oldest read holds floats");
    out.resize(static_cast<size_t>(s.width) * s.height * 4);
    copy_oldest(out.data(), out.size());
}

void PboReadback::collect(std::vector<float>& out) {
    const Slot& s = oldest();
    if (s.format != PixelFormat::RgbaFloat) throw std::logic_error("pbo read-back: the oldest read holds bytes");
    out.resize(static_cast<size_t>(s.width) * s.height * 4);
    copy_oldest(out.data(), out.size() * sizeof(float));
}

}  // namespace cupola
