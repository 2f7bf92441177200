#include "output/warp_pass.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "dome/acuity_blur.hpp"
#include "gl/gl_api.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {

void require(bool ok, const ProjectorWarp& w, const std::string& what) {
    if (!ok) throw std::invalid_argument(w.source + ": " + what);
}

void validate(const ProjectorWarp& w) {
    require(w.raster_width > 0 && w.raster_height > 0, w, "projector raster size is not positive");
    const WarpGrid& g = w.grid;
    require(g.columns >= 2 && g.rows >= 2, w, "warp grid is smaller than 2x2");
    const size_t points = static_cast<size_t>(g.columns) * g.rows;
    require(g.uv.size() == points, w, "warp grid holds " + std::to_string(g.uv.size()) + " points, not columns x rows");
    require(g.intensity.empty() || g.intensity.size() == points, w, "intensity is not one value per grid point");
    for (const BlendMap* m : {&w.alpha, &w.beta})
        require(m->empty() ||
                    (m->width > 0 && m->height > 0 && m->value.size() == static_cast<size_t>(m->width) * m->height),
                w, std::string(m == &w.alpha ? "alpha" : "beta") + " map size does not match its values");
    require(w.projector_gamma > 0.0, w, "projector gamma is not positive");
}

// Grid points as texels (u, v, intensity, 0); texel row j is grid row j (j = 0 the top).
std::vector<glm::vec4> grid_texels(const WarpGrid& g) {
    std::vector<glm::vec4> t(g.uv.size());
    for (size_t k = 0; k < t.size(); ++k)
        t[k] = glm::vec4(static_cast<float>(g.uv[k].x), static_cast<float>(g.uv[k].y),
                         g.intensity.empty() ? 1.0f : g.intensity[k], 0.0f);
    return t;
}

std::unique_ptr<GlTexture> map_texture(const BlendMap& m, float empty_value) {
    if (m.empty()) {
        const glm::vec4 one(empty_value);
        return std::make_unique<GlTexture>(1, 1, &one, GL_LINEAR);
    }
    std::vector<glm::vec4> t(m.value.size());
    for (size_t k = 0; k < t.size(); ++k) t[k] = glm::vec4(m.value[k]);
    return std::make_unique<GlTexture>(m.width, m.height, t.data(), GL_LINEAR);
}

// Colour attachment 0 of fbo as RGBA, row 0 the TOP row (GL's row 0 is the bottom).
template <typename T>
std::vector<T> read_rows(GLuint fbo, int w, int h, GLenum type) {
    const size_t row = static_cast<size_t>(w) * 4;
    std::vector<T> gl_rows(row * h), out(row * h);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, type, gl_rows.data());
    gl::check("warp pass read-back");
    for (int y = 0; y < h; ++y)
        std::memcpy(&out[static_cast<size_t>(y) * row], &gl_rows[static_cast<size_t>(h - 1 - y) * row],
                    row * sizeof(T));
    return out;
}

}  // namespace

// The GL objects of one pass. The slave/gl wrappers hold the float textures, the program and the
// linear target; the encoded RGBA8 target, the framebuffers drawing both at once and the
// content's sampler are plain GL names owned here.
struct WarpPass::Gpu {
    GlProgram program{"fullscreen.vert", "warp.frag"};
    GlEmptyVertexArray triangle;
    std::unique_ptr<GlTexture> grid, alpha, beta, linear;
    GLuint encoded = 0, linear_fbo = 0, encoded_fbo = 0, both_fbo = 0, sampler = 0;

    // w == nullptr: identity (a placeholder grid, no maps).
    Gpu(const ProjectorWarp* w, int width, int height);
    ~Gpu() {
        glDeleteSamplers(1, &sampler);
        glDeleteFramebuffers(1, &both_fbo);
        glDeleteFramebuffers(1, &encoded_fbo);
        glDeleteFramebuffers(1, &linear_fbo);
        glDeleteTextures(1, &encoded);
    }
    void make_targets(int width, int height);
};

WarpPass::Gpu::Gpu(const ProjectorWarp* w, int width, int height) {
    const WarpGrid placeholder{2, 2, std::vector<glm::dvec2>(4, glm::dvec2(0.5)), {}};
    const WarpGrid& g = w ? w->grid : placeholder;
    const std::vector<glm::vec4> texels = grid_texels(g);
    grid = std::make_unique<GlTexture>(g.columns, g.rows, texels.data(), GL_NEAREST);
    alpha = map_texture(w ? w->alpha : BlendMap{}, 1.0f);
    beta = map_texture(w ? w->beta : BlendMap{}, 0.0f);
    glCreateSamplers(1, &sampler);
    glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    make_targets(width, height);
}

void WarpPass::Gpu::make_targets(int width, int height) {
    linear = std::make_unique<GlTexture>(width, height, nullptr, GL_NEAREST);
    glCreateFramebuffers(1, &linear_fbo);
    glNamedFramebufferTexture(linear_fbo, GL_COLOR_ATTACHMENT0, linear->id(), 0);
    glCreateTextures(GL_TEXTURE_2D, 1, &encoded);
    glTextureStorage2D(encoded, 1, GL_RGBA8, width, height);
    glCreateFramebuffers(1, &encoded_fbo);
    glNamedFramebufferTexture(encoded_fbo, GL_COLOR_ATTACHMENT0, encoded, 0);
    glCreateFramebuffers(1, &both_fbo);
    glNamedFramebufferTexture(both_fbo, GL_COLOR_ATTACHMENT0, linear->id(), 0);
    glNamedFramebufferTexture(both_fbo, GL_COLOR_ATTACHMENT1, encoded, 0);
    const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(both_fbo, 2, both);
    for (GLuint fbo : {linear_fbo, encoded_fbo, both_fbo})
        if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("warp pass: projector framebuffer " + std::to_string(width) + "x" +
                                     std::to_string(height) + " is incomplete");
    gl::check("warp pass targets");
}

WarpPass::WarpPass(std::optional<ProjectorWarp> warp, int content_width, int content_height, WarpOptions options)
    : content_width_(content_width), content_height_(content_height), options_(options) {
    if (content_width <= 0 || content_height <= 0)
        throw std::invalid_argument("warp pass: content size " + std::to_string(content_width) + "x" +
                                    std::to_string(content_height) + " is not positive");
    if (options_.supersample_filter < 1 || options_.supersample_filter > 8)
        throw std::invalid_argument("warp pass: supersample_filter " + std::to_string(options_.supersample_filter) +
                                    " is outside 1..8");
    if (warp) {
        validate(*warp);
        width_ = warp->raster_width;
        height_ = warp->raster_height;
    } else {
        options_.encode = WarpOptions::Encode::Srgb;
        width_ = content_width;
        height_ = content_height;
    }
    warp_ = std::move(warp);
    gpu_ = std::make_unique<Gpu>(warp_ ? &*warp_ : nullptr, width_, height_);
}

WarpPass::~WarpPass() = default;

void WarpPass::set_acuity_blur(double sigma_rad) const {
    const GlProgram& p = gpu_->program;
    const auto& view = options_.content_view;
    const bool on = view && acuity_blur_needed(sigma_rad, (view->tan_left() + view->tan_right()) / content_width_);
    p.set("u_acuity_sigma_rad", on ? static_cast<float>(sigma_rad) : 0.0f);
    if (!on) return;
    p.set("u_content_tan", glm::vec4(view->tan_left(), view->tan_right(), view->tan_down(), view->tan_up()));
    p.set("u_content_to_dome", glm::mat3(view->rotation()));
}

void WarpPass::draw(unsigned content_texture, double exposure, double tone_white, double night_adapted_cd_m2,
                    double acuity_sigma_rad) {
    const GlProgram& p = gpu_->program;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gpu_->both_fbo);
    glViewport(0, 0, width_, height_);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    p.use();
    glBindTextureUnit(0, content_texture);
    glBindSampler(0, gpu_->sampler);
    gpu_->grid->bind(1);
    gpu_->alpha->bind(2);
    gpu_->beta->bind(3);
    p.set("u_content", 0);
    p.set("u_grid", 1);
    p.set("u_alpha", 2);
    p.set("u_beta", 3);
    p.set("u_raster", glm::vec2(width_, height_));
    p.set("u_content_size", glm::vec2(content_width_, content_height_));
    p.set("u_exposure", static_cast<float>(exposure));
    p.set("u_tone_white", static_cast<float>(tone_white));
    p.set("u_night_adapted_cd_m2", static_cast<float>(night_adapted_cd_m2));
    set_acuity_blur(acuity_sigma_rad);
    p.set("u_gamma", static_cast<float>(warp_ ? warp_->projector_gamma : 2.2));
    p.set("u_identity", warp_ ? 0 : 1);
    const bool srgb = options_.encode == WarpOptions::Encode::Srgb;
    p.set("u_encode", srgb ? shading::PROJECTOR_ENCODE_SRGB : shading::PROJECTOR_ENCODE_GAMMA);
    p.set("u_max_taps", options_.supersample_filter);
    gpu_->triangle.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindSampler(0, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gpu_->encoded_fbo);
    gl::check("warp pass draw");
}

unsigned WarpPass::linear_framebuffer() const { return gpu_->linear_fbo; }
unsigned WarpPass::encoded_framebuffer() const { return gpu_->encoded_fbo; }
unsigned WarpPass::linear_texture() const { return gpu_->linear->id(); }
unsigned WarpPass::encoded_texture() const { return gpu_->encoded; }
int WarpPass::width() const { return width_; }
int WarpPass::height() const { return height_; }

Image WarpPass::read_linear() const {
    Image img;
    img.width = width_;
    img.height = height_;
    img.rgba = read_rows<float>(gpu_->linear_fbo, img.width, img.height, GL_FLOAT);
    return img;
}

std::vector<uint8_t> WarpPass::read_encoded() const {
    return read_rows<uint8_t>(gpu_->encoded_fbo, width_, height_, GL_UNSIGNED_BYTE);
}

}  // namespace cupola
