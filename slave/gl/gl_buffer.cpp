#include "gl/gl_buffer.hpp"

#include <stdexcept>
#include <string>

namespace cupola {

GlIndexBuffer::GlIndexBuffer(const std::vector<GLuint>& indices) : count_(indices.size()) {
    glCreateBuffers(1, &ebo_);
    glNamedBufferData(ebo_, static_cast<GLsizeiptr>(indices.size() * sizeof(GLuint)),
                      indices.empty() ? nullptr : indices.data(), GL_STATIC_DRAW);
}

GlVertexBuffer::GlVertexBuffer(std::vector<int> components) {
    glCreateVertexArrays(1, &vao_);
    glCreateBuffers(1, &vbo_);
    for (int c : components) stride_ += c;
    glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, stride_ * static_cast<GLsizei>(sizeof(float)));
    int offset = 0;
    for (GLuint i = 0; i < components.size(); ++i) {
        glEnableVertexArrayAttrib(vao_, i);
        glVertexArrayAttribFormat(vao_, i, components[i], GL_FLOAT, GL_FALSE,
                                  static_cast<GLuint>(offset * sizeof(float)));
        glVertexArrayAttribBinding(vao_, i, 0);
        offset += components[i];
    }
}

GlVertexBuffer::~GlVertexBuffer() {
    if (ebo_) glDeleteBuffers(1, &ebo_);
    glDeleteBuffers(1, &vbo_);
    glDeleteVertexArrays(1, &vao_);
}

void GlVertexBuffer::add_float_attribute(GLuint location, GLuint buffer, int components) {
    if (components < 1 || components > 4)
        throw std::invalid_argument("vertex attribute " + std::to_string(location) + ": " + std::to_string(components) +
                                    " components (1 to 4)");
    const GLuint binding = location + 1;  // binding 0 is the owned buffer's
    glVertexArrayVertexBuffer(vao_, binding, buffer, 0, static_cast<GLsizei>(components * sizeof(float)));
    glEnableVertexArrayAttrib(vao_, location);
    glVertexArrayAttribFormat(vao_, location, components, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, location, binding);
}

void GlVertexBuffer::upload(const std::vector<float>& data) {
    glNamedBufferData(vbo_, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.empty() ? nullptr : data.data(),
                      GL_STATIC_DRAW);
    count_ = stride_ ? static_cast<int>(data.size()) / stride_ : 0;
}

void GlVertexBuffer::upload_indices(const std::vector<GLuint>& indices) {
    if (!ebo_) {
        glCreateBuffers(1, &ebo_);
        glVertexArrayElementBuffer(vao_, ebo_);
    }
    glNamedBufferData(ebo_, static_cast<GLsizeiptr>(indices.size() * sizeof(GLuint)),
                      indices.empty() ? nullptr : indices.data(), GL_STATIC_DRAW);
}

}  // namespace cupola
