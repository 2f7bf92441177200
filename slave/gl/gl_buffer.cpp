#include "gl/gl_buffer.hpp"

namespace cupola {

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
    glDeleteBuffers(1, &vbo_);
    glDeleteVertexArrays(1, &vao_);
}

void GlVertexBuffer::add_float_attribute(GLuint location, GLuint buffer) {
    const GLuint binding = location + 1;  // binding 0 is the owned buffer's
    glVertexArrayVertexBuffer(vao_, binding, buffer, 0, static_cast<GLsizei>(sizeof(float)));
    glEnableVertexArrayAttrib(vao_, location);
    glVertexArrayAttribFormat(vao_, location, 1, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, location, binding);
}

void GlVertexBuffer::upload(const std::vector<float>& data) {
    glNamedBufferData(vbo_, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.empty() ? nullptr : data.data(),
                      GL_STATIC_DRAW);
    count_ = stride_ ? static_cast<int>(data.size()) / stride_ : 0;
}

}  // namespace cupola
