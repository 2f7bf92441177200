#include "output/warp_pass.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace cupola {

namespace {

const char* kVertex = R"(#version 450 core
void main() {
    vec2 p = vec2((gl_VertexID == 1) ? 3.0 : -1.0, (gl_VertexID == 2) ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})";

// sRGB encode (IEC 61966-2-1:1999 §5.2) of clamp(exposure * linear), as common/image/frame_image.
const char* kFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D u_content;
uniform float u_exposure;
layout(location = 0) out vec4 o_linear;
layout(location = 1) out vec4 o_encoded;
vec3 srgb(vec3 x) {
    x = clamp(x, 0.0, 1.0);
    return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, greaterThan(x, vec3(0.0031308)));
}
void main() {
    vec4 c = texelFetch(u_content, ivec2(gl_FragCoord.xy), 0);
    o_linear = vec4(c.rgb * u_exposure, c.a);
    o_encoded = vec4(srgb(c.rgb * u_exposure), clamp(c.a, 0.0, 1.0));
})";

GLuint compile(GLenum stage, const char* text) {
    const GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = {};
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        throw std::runtime_error(std::string("warp pass shader: ") + log);
    }
    return s;
}

}  // namespace

EncodedTarget::EncodedTarget(int width, int height) : width_(width), height_(height) {
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA8, width, height);
    glCreateFramebuffers(1, &fbo_);
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, texture_, 0);
    if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("RGBA8 framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is incomplete");
    gl::check("RGBA8 target");
}

EncodedTarget::~EncodedTarget() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &texture_);
}

void EncodedTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glNamedFramebufferReadBuffer(fbo_, GL_COLOR_ATTACHMENT0);
    glViewport(0, 0, width_, height_);
}

EncodedImage EncodedTarget::read() const {
    EncodedImage img;
    img.width = width_;
    img.height = height_;
    std::vector<uint8_t> gl_rows(static_cast<size_t>(width_) * height_ * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, gl_rows.data());
    gl::check("glReadPixels (RGBA8)");
    img.rgba.resize(gl_rows.size());
    const size_t row = static_cast<size_t>(width_) * 4;
    for (int y = 0; y < height_; ++y)  // GL row 0 is the bottom
        std::memcpy(&img.rgba[static_cast<size_t>(y) * row], &gl_rows[static_cast<size_t>(height_ - 1 - y) * row], row);
    return img;
}

WarpPass::WarpPass(std::optional<ProjectorWarp> warp, int content_width, int content_height, WarpOptions)
    : linear_(content_width, content_height), encoded_(content_width, content_height) {
    if (warp) throw std::runtime_error("the warp pass is not available in this build (" + warp->source + ")");
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertex), fs = compile(GL_FRAGMENT_SHADER, kFragment);
    program_ = glCreateProgram();
    glAttachShader(program_, vs);
    glAttachShader(program_, fs);
    glLinkProgram(program_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    glCreateFramebuffers(1, &both_);
    glNamedFramebufferTexture(both_, GL_COLOR_ATTACHMENT0, linear_.color(0).id(), 0);
    glNamedFramebufferTexture(both_, GL_COLOR_ATTACHMENT1, encoded_.texture(), 0);
    const GLenum bufs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(both_, 2, bufs);
    gl::check("warp pass program");
}

WarpPass::~WarpPass() {
    glDeleteFramebuffers(1, &both_);
    glDeleteProgram(program_);
}

void WarpPass::draw(const GlTexture& content, double exposure) {
    glBindFramebuffer(GL_FRAMEBUFFER, both_);
    glViewport(0, 0, linear_.width(), linear_.height());
    glDisable(GL_BLEND);
    glUseProgram(program_);
    glUniform1f(glGetUniformLocation(program_, "u_exposure"), static_cast<float>(exposure));
    content.bind(0);
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gl::check("warp pass");
}

}  // namespace cupola
