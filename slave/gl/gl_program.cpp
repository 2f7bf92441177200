#include "gl/gl_program.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <stdexcept>
#include <vector>

#include "shading/shader_sources.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {

std::string info_log(GLuint obj, bool program) {
    GLint len = 0;
    program ? glGetProgramiv(obj, GL_INFO_LOG_LENGTH, &len) : glGetShaderiv(obj, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> buf(static_cast<size_t>(len > 1 ? len : 1), '\0');
    program ? glGetProgramInfoLog(obj, len, nullptr, buf.data()) : glGetShaderInfoLog(obj, len, nullptr, buf.data());
    return std::string(buf.data());
}

GLuint compile(GLenum stage, const std::string& name, const std::string& prelude) {
    const std::string text = GlProgram::assemble(name, prelude);
    const GLuint s = glCreateShader(stage);
    const char* src = text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = info_log(s, false);
        glDeleteShader(s);
        throw std::runtime_error("shader \"" + name + "\" failed to compile (line numbers: source string 0 = " +
                                 "the shared files, 1 = the shader itself):\n" + log);
    }
    return s;
}

}  // namespace

std::string GlProgram::assemble(const std::string& shader_name, const std::string& prelude) {
    const std::string& src = shader_source(shader_name);
    const auto eol = src.find('\n');
    if (src.rfind("#version", 0) != 0 || eol == std::string::npos)
        throw std::runtime_error("shader \"" + shader_name + "\" must start with a #version line");
    std::string out = src.substr(0, eol + 1) + prelude;
    out += "#line 1 0\n";
    for (const char* f : kSharedShadingFiles) out += shader_source(f) + "\n";
    out += "#line 2 1\n";
    out += src.substr(eol + 1);
    return out;
}

GlProgram::GlProgram(const std::string& vertex, const std::string& fragment, const std::string& fragment_prelude) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex, "");
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragment, fragment_prelude);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    id_ = glCreateProgram();
    glAttachShader(id_, vs);
    glAttachShader(id_, fs);
    glLinkProgram(id_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        const std::string log = info_log(id_, true);
        glDeleteProgram(id_);
        throw std::runtime_error("program \"" + vertex + "\" + \"" + fragment + "\" failed to link:\n" + log);
    }
}

GlProgram::~GlProgram() {
    if (id_) glDeleteProgram(id_);
}

void GlProgram::use() const { glUseProgram(id_); }
void GlProgram::set(const char* n, float v) const { glUniform1f(loc(n), v); }
void GlProgram::set(const char* n, int v) const { glUniform1i(loc(n), v); }
void GlProgram::set(const char* n, const glm::vec2& v) const { glUniform2fv(loc(n), 1, glm::value_ptr(v)); }
void GlProgram::set(const char* n, const glm::vec3& v) const { glUniform3fv(loc(n), 1, glm::value_ptr(v)); }
void GlProgram::set(const char* n, const glm::vec4& v) const { glUniform4fv(loc(n), 1, glm::value_ptr(v)); }
void GlProgram::set(const char* n, const glm::mat3& m) const {
    glUniformMatrix3fv(loc(n), 1, GL_FALSE, glm::value_ptr(m));
}
void GlProgram::set(const char* n, const glm::mat4& m) const {
    glUniformMatrix4fv(loc(n), 1, GL_FALSE, glm::value_ptr(m));
}
void GlProgram::set(const char* n, const glm::vec3* v, int count) const {
    glUniform3fv(loc(n), count, glm::value_ptr(v[0]));
}
void GlProgram::set(const char* n, const glm::vec4* v, int count) const {
    glUniform4fv(loc(n), count, glm::value_ptr(v[0]));
}
void GlProgram::set(const char* n, const glm::mat3* m, int count) const {
    glUniformMatrix3fv(loc(n), count, GL_FALSE, glm::value_ptr(m[0]));
}

}  // namespace cupola
