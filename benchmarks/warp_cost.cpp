// Cost of the projector pass (slave/output/warp_pass): a 1920x1200 projector raster drawn from a
// 2048^2 channel through a smooth dome-projector warp (barrel distortion and keystone, about 1.1
// content texels per projector pixel), with raster-size alpha and beta maps, on a 32x32 grid
// (MPCDI geometry level 1) and a per-pixel grid (level 2), with the footprint filter off (one
// tap) and on (up to 4x4 taps). Each in ms per pass and as a ratio to a trivial full-screen pass
// (one texel copied per pixel into an RGBA32F target of the raster's size) timed in the same run.
// --images DIR also writes the pictures of docs/images: warp-dome-projector.png (a test card
// through the warp, blended and encoded for the projector) and warp-filter.png (a crop of the
// one-texel checker through the warp, one tap on the left, the footprint filter on the right), and
// prints how far each is from the checker's area mean per pixel (aliasing).
//   build/bin/warp_cost [--width 1920 --height 1200 --content 2048 --frames 10] [--images DIR]
#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gl/egl_context.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "output/warp_pass.hpp"
#include "util/cli_parse.hpp"

using namespace cupola;

namespace {

// A smooth projector -> content map: barrel distortion about the raster centre and a slight
// keystone, covering most of the content, the way a square frustum render fills a 16:10
// projector's frustum (about 1 texel per pixel across, 1.6 up).
glm::dvec2 dome_uv(double px, double py, int w, int h) {
    const double x = (px / w * 2.0 - 1.0), y = (1.0 - py / h * 2.0);
    const double r2 = x * x + y * y, k = 1.0 - 0.1 * r2, key = 1.0 + 0.05 * y;
    return {0.5 + 0.47 * x * k * key, 0.5 + 0.47 * y * k};
}

ProjectorWarp dome_warp(int w, int h, int columns, int rows) {
    ProjectorWarp warp;
    warp.source = "benchmark dome warp";
    warp.raster_width = w;
    warp.raster_height = h;
    warp.grid.columns = columns;
    warp.grid.rows = rows;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const glm::dvec2 p = grid_point_pixel(i, j, columns, rows, w, h);
            warp.grid.uv.push_back(dome_uv(p.x, p.y, w, h));
        }
    warp.alpha = BlendMap{w, h, std::vector<float>(static_cast<size_t>(w) * h)};
    warp.beta = BlendMap{w, h, std::vector<float>(static_cast<size_t>(w) * h, 0.02f)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)  // a blend ramp over the right fifth
            warp.alpha.value[static_cast<size_t>(y) * w + x] = std::clamp(5.0f * (1.0f - float(x) / w), 0.0f, 1.0f);
    warp.projector_gamma = 2.2;
    return warp;
}

// A test card: a grid line every 1/16 of the content, quadrants tinted, a bright centre disc.
std::vector<glm::vec4> test_card(int n) {
    std::vector<glm::vec4> t(static_cast<size_t>(n) * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const bool line = (x * 16 / n) != ((x + 2) * 16 / n) || (y * 16 / n) != ((y + 2) * 16 / n);
            const double r = std::hypot(x - n / 2.0, y - n / 2.0) / n;
            glm::vec4 c(x < n / 2 ? 0.5f : 0.15f, y < n / 2 ? 0.15f : 0.5f, 0.3f, 1.0f);  // y up: bottom is green
            if (r < 0.06) c = glm::vec4(1.0f);
            if (line) c = glm::vec4(0.9f, 0.9f, 0.9f, 1.0f);
            t[static_cast<size_t>(y) * n + x] = c;
        }
    return t;
}

void write_png(const std::string& path, int w, int h, const std::vector<uint8_t>& rgba) {
    auto out = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::UINT8);
    if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) || !out->close())
        throw std::runtime_error("cannot write " + path);
    std::printf("wrote %s\n", path.c_str());
}

// Columns [x0, x0 + cw) and rows [y0, y0 + ch) of an RGBA8 image w pixels wide, each pixel
// repeated 2x2 so the moire is visible.
std::vector<uint8_t> crop(const std::vector<uint8_t>& rgba, int w, int x0, int y0, int cw, int ch) {
    std::vector<uint8_t> out;
    for (int y = y0; y < y0 + ch; ++y)
        for (int twice = 0; twice < 2; ++twice)
            for (int x = x0; x < x0 + cw; ++x)
                for (int r = 0; r < 2; ++r)
                    out.insert(out.end(), rgba.begin() + (static_cast<size_t>(y) * w + x) * 4,
                               rgba.begin() + (static_cast<size_t>(y) * w + x + 1) * 4);
    return out;
}

// The RMS difference of the linear red channel from the checker's area mean over each pixel
// (6 x 6 points of the analytic map per pixel): what is left is aliasing.
double checker_rms(const Image& lin, int n) {
    double sum = 0.0;
    for (int y = 0; y < lin.height; ++y)
        for (int x = 0; x < lin.width; ++x) {
            double mean = 0.0;
            for (int j = 0; j < 6; ++j)
                for (int i = 0; i < 6; ++i) {
                    const glm::dvec2 uv = dome_uv(x + (i + 0.5) / 6.0, y + (j + 0.5) / 6.0, lin.width, lin.height);
                    mean += ((int(std::floor(uv.x * n)) + int(std::floor(uv.y * n))) % 2) / 36.0;
                }
            const double e = lin.pixel(x, y)[0] - mean;
            sum += e * e;
        }
    return std::sqrt(sum / (static_cast<double>(lin.width) * lin.height));
}

void write_images(const std::string& dir, const GlTexture& checker, int width, int height) {
    const int n = 1024, w = 480, h = 300;
    const std::vector<glm::vec4> card = test_card(n);
    const GlTexture card_texture(n, n, card.data(), GL_NEAREST);
    WarpPass dome(dome_warp(w, h, 32, 32), n, n);
    dome.draw(card_texture.id(), 1.0);
    write_png(dir + "/warp-dome-projector.png", w, h, dome.read_encoded());
    const int cw = 120, ch = 120, x0 = width - 3 * cw / 2, y0 = height / 2 - ch / 2;
    std::vector<uint8_t> both;
    std::vector<std::vector<uint8_t>> halves;
    for (int taps : {1, 4}) {
        ProjectorWarp warp = dome_warp(width, height, width, height);
        warp.alpha = warp.beta = BlendMap{};
        WarpPass pass(warp, checker.width(), checker.height(), WarpOptions{WarpOptions::Encode::Gamma, taps});
        pass.draw(checker.id(), 1.0);
        halves.push_back(crop(pass.read_encoded(), width, x0, y0, cw, ch));
        std::printf("one-texel checker, per-pixel grid, %s: rms error against the area mean %.4f\n",
                    taps == 1 ? "one tap" : "footprint filter", checker_rms(pass.read_linear(), checker.width()));
    }
    for (int y = 0; y < 2 * ch; ++y)
        for (const auto& half : halves)
            both.insert(both.end(), half.begin() + static_cast<size_t>(y) * 2 * cw * 4,
                        half.begin() + static_cast<size_t>(y + 1) * 2 * cw * 4);
    write_png(dir + "/warp-filter.png", 4 * cw, 2 * ch, both);
}

double time_ms(const std::function<void()>& draw, int frames) {
    draw();  // warm-up: shader compile, first upload
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) draw();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / frames;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Projector warp pass cost (ms per pass and ratio to a trivial full-screen pass)"};
    int width = 1920, height = 1200, content_size = 2048, frames = 10;
    app.add_option("--width", width, "projector raster width")->check(CLI::Range(16, 8192));
    app.add_option("--height", height, "projector raster height")->check(CLI::Range(16, 8192));
    app.add_option("--content", content_size, "channel render width and height")->check(CLI::Range(16, 8192));
    app.add_option("--frames", frames, "timed passes per case and round")->check(CLI::Range(1, 100000));
    std::string images;
    app.add_option("--images", images, "also write docs/images/warp-*.png into this folder")
        ->check(CLI::ExistingDirectory);
    if (auto rc = parse_command_line(app, argc, argv, "warp_cost")) return *rc;

    EglContext gl(-1);
    std::vector<glm::vec4> texels(static_cast<size_t>(content_size) * content_size);
    for (size_t k = 0; k < texels.size(); ++k)  // the finest detail a channel holds: a one-texel checker
        texels[k] = glm::vec4(glm::vec3(float((k + k / content_size) % 2)), 1.0f);
    const GlTexture content(content_size, content_size, texels.data(), GL_NEAREST);
    if (!images.empty()) write_images(images, content, width, height);

    GlFramebuffer trivial_target(width, height);
    GlProgram trivial("fullscreen.vert", "fullscreen_copy.frag");
    GlEmptyVertexArray triangle;
    struct Case {
        std::string name;
        std::function<void()> draw;
    };
    std::vector<Case> cases;
    cases.push_back({"trivial full-screen pass", [&] {
                         trivial_target.bind();
                         trivial.use();
                         content.bind(0);
                         trivial.set("u_source", 0);
                         triangle.bind();
                         glDrawArrays(GL_TRIANGLES, 0, 3);
                     }});
    std::vector<std::unique_ptr<WarpPass>> passes;
    for (int grid : {32, 0})
        for (int taps : {1, 4}) {
            const ProjectorWarp w = grid ? dome_warp(width, height, 32, 32) : dome_warp(width, height, width, height);
            passes.push_back(std::make_unique<WarpPass>(w, content_size, content_size,
                                                        WarpOptions{WarpOptions::Encode::Gamma, taps}));
            WarpPass* p = passes.back().get();
            cases.push_back({std::string(grid ? "32x32 grid" : "per-pixel grid") +
                                 (taps == 1 ? ", one tap" : ", footprint filter (<= 4x4)"),
                             [p, &content] { p->draw(content.id(), 1.0); }});
        }
    std::printf("renderer: %s; raster %dx%d from a %d^2 channel, %d passes per case and round\n",
                gl.info().renderer.c_str(), width, height, content_size, frames);
    // Interleaved rounds, the median of 5 kept, so drifts of the machine hit every case alike.
    std::vector<std::vector<double>> ms(cases.size());
    for (int round = 0; round < 5; ++round)
        for (size_t i = 0; i < cases.size(); ++i) ms[i].push_back(time_ms(cases[i].draw, frames));
    const double base = median(ms[0]);
    std::printf("| pass | ms | ratio to the trivial pass |\n|---|---|---|\n");
    for (size_t i = 0; i < cases.size(); ++i)
        std::printf("| %s | %.2f | %.2f |\n", cases[i].name.c_str(), median(ms[i]), median(ms[i]) / base);
    return 0;
}
