#pragma once
// A vertex array object with one interleaved float vertex buffer (RAII).
#include <cstddef>
#include <vector>

#include "gl/gl_api.hpp"

namespace cupola {

// An index buffer of its own (RAII), for vertex arrays that share their triangles
// (GlVertexBuffer::share_indices).
class GlIndexBuffer {
public:
    explicit GlIndexBuffer(const std::vector<GLuint>& indices);
    ~GlIndexBuffer() { glDeleteBuffers(1, &ebo_); }
    GlIndexBuffer(const GlIndexBuffer&) = delete;
    GlIndexBuffer& operator=(const GlIndexBuffer&) = delete;
    GLuint id() const { return ebo_; }
    size_t count() const { return count_; }

private:
    GLuint ebo_ = 0;
    size_t count_ = 0;
};

class GlVertexBuffer {
public:
    // components: floats per attribute, in order (attribute locations 0, 1, ...).
    explicit GlVertexBuffer(std::vector<int> components);
    ~GlVertexBuffer();
    GlVertexBuffer(const GlVertexBuffer&) = delete;
    GlVertexBuffer& operator=(const GlVertexBuffer&) = delete;

    // Replaces the contents; data holds whole vertices.
    void upload(const std::vector<float>& data);
    // Replaces the index buffer (made on first use) that indexed draws of this array read.
    void upload_indices(const std::vector<GLuint>& indices);
    // Indexed draws read a shared index buffer (not owned; it must outlive this array's draws):
    // arrays with the same triangles share one.
    void share_indices(const GlIndexBuffer& indices) { glVertexArrayElementBuffer(vao_, indices.id()); }
    int vertex_count() const { return count_; }
    void bind() const { glBindVertexArray(vao_); }
    // Takes one more attribute, `location`, from another buffer (not owned): `components` floats
    // (1 to 4) per vertex, tightly packed.
    void add_float_attribute(GLuint location, GLuint buffer, int components = 1);

private:
    GLuint vao_ = 0, vbo_ = 0, ebo_ = 0;
    int stride_ = 0;  // floats per vertex
    int count_ = 0;
};

// An empty vertex array, for draws whose vertices come from gl_VertexID.
class GlEmptyVertexArray {
public:
    GlEmptyVertexArray() { glCreateVertexArrays(1, &vao_); }
    ~GlEmptyVertexArray() { glDeleteVertexArrays(1, &vao_); }
    GlEmptyVertexArray(const GlEmptyVertexArray&) = delete;
    GlEmptyVertexArray& operator=(const GlEmptyVertexArray&) = delete;
    void bind() const { glBindVertexArray(vao_); }

private:
    GLuint vao_ = 0;
};

}  // namespace cupola
