#pragma once
// A linked GLSL program built from embedded shaders (shaders/), with the shared shading files
// (shaders/shared/*.glsl, also compiled as C++) inserted after each stage's #version line.
#include <glm/glm.hpp>

#include <string>

#include "gl/gl_api.hpp"

namespace cupola {

class GlProgram {
public:
    // vertex/fragment: embedded shader names, e.g. "stars.vert". fragment_prelude: lines put right
    // after the fragment shader's #version (e.g. a #define choosing a variant). Throws
    // std::runtime_error naming the shader and quoting the driver's info log when a stage fails
    // to compile or link.
    GlProgram(const std::string& vertex, const std::string& fragment, const std::string& fragment_prelude = "");
    ~GlProgram();
    GlProgram(const GlProgram&) = delete;
    GlProgram& operator=(const GlProgram&) = delete;

    void use() const;
    GLuint id() const { return id_; }

    // Uniform setters (the program must be in use); unknown names are ignored, as GL does.
    void set(const char* name, float v) const;
    void set(const char* name, int v) const;
    void set(const char* name, const glm::vec2& v) const;
    void set(const char* name, const glm::vec3& v) const;
    void set(const char* name, const glm::vec4& v) const;
    void set(const char* name, const glm::mat3& m) const;
    void set(const char* name, const glm::mat4& m) const;
    void set(const char* name, const glm::vec3* v, int count) const;
    void set(const char* name, const glm::vec4* v, int count) const;
    void set(const char* name, const glm::mat3* m, int count) const;

    // The text handed to the driver for one stage (the shader plus the shared files).
    static std::string assemble(const std::string& shader_name, const std::string& prelude = "");

private:
    GLint loc(const char* name) const { return glGetUniformLocation(id_, name); }
    GLuint id_ = 0;
};

}  // namespace cupola
