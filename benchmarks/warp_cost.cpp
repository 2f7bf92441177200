// Cost of the projector pass (slave/output/warp_pass): a 1920x1200 projector raster drawn from a
// 2048^2 channel through a smooth dome-projector warp (barrel distortion and keystone, about 1.1
// content texels per projector pixel), with raster-size alpha and beta maps, on a 32x32 grid
// (MPCDI geometry level 1) and a per-pixel grid (level 2), with the footprint filter off (one
// tap) and on (up to 4x4 taps). Each in ms per pass and as a ratio to a trivial full-screen pass
// (one texel copied per pixel into an RGBA32F target of the raster's size) timed in the same run.
//   build/bin/warp_cost [--width 1920 --height 1200 --content 2048 --frames 10]
#include <CLI/CLI.hpp>

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
// keystone, covering most of the content.
glm::dvec2 dome_uv(double px, double py, int w, int h) {
    const double aspect = static_cast<double>(w) / h;
    const double x = (px / w * 2.0 - 1.0), y = (1.0 - py / h * 2.0) / aspect;
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
        for (int i = 0; i < columns; ++i)
            warp.grid.uv.push_back(dome_uv((i + 0.5) * w / columns, (j + 0.5) * h / rows, w, h));
    warp.alpha = BlendMap{w, h, std::vector<float>(static_cast<size_t>(w) * h)};
    warp.beta = BlendMap{w, h, std::vector<float>(static_cast<size_t>(w) * h, 0.02f)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)  // a blend ramp over the right fifth
            warp.alpha.value[static_cast<size_t>(y) * w + x] = std::clamp(5.0f * (1.0f - float(x) / w), 0.0f, 1.0f);
    warp.projector_gamma = 2.2;
    return warp;
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
    if (auto rc = parse_command_line(app, argc, argv, "warp_cost")) return *rc;

    EglContext gl(-1);
    std::vector<glm::vec4> texels(static_cast<size_t>(content_size) * content_size);
    for (size_t k = 0; k < texels.size(); ++k)  // fine detail everywhere: a 1-texel checker on a ramp
        texels[k] = glm::vec4(float((k + k / content_size) % 2), float(k % content_size) / content_size, 0.5f, 1.0f);
    const GlTexture content(content_size, content_size, texels.data(), GL_NEAREST);

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
