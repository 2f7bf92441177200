// Speed against error of the eclipse shadow modes (shaders/shared/eclipse_shadow.glsl).
//   eclipse_speed_vs_error [--size N] [--reps N] [--csv FILE] [--limb-u U] [--order N]
// Speed: a full-screen pass at N x N (default 1024) through EGL evaluating one mode per pixel for
// a varied (a, s) per pixel, read from a parameter texture: a = 0.9 .. 1.1 across the frame
// (Sun-Moon ratios), s = 0 .. 1 + a up the frame (antumbra or umbra, then the penumbra). Each
// program holds one mode's code only (the mode is a compile-time constant); "none" fetches the
// parameters and writes them, and is subtracted from the others. Median of --reps frames per mode
// (default 15), each drawn and finished (glFinish) on its own, the modes taking turns frame by
// frame, after 2 warm-up frames each.
// Error: |visible fraction - reference| (common/eclipse/eclipse_reference, double) of what the
// GPU computes, over the penumbra (inner contact |1 - a| to first contact 1 + a) of
// a = 0.9 .. 1.1 (201 x 401 points) and of a = 3.7 (Earth seen from the Moon, 4001 points).
// A second table: LUT size against build time, memory and error (C++ build of the lookup, which
// tests/test_eclipse_shadow.cpp shows equal to the GPU's within 3e-7).
// Prints Markdown tables; --csv also writes the figures for tools/plot_eclipse_speed_vs_error.py.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "eclipse/eclipse_reference.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_api.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include <memory>

#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "shading/shared_shading.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

constexpr int kModeNone = 4;  // eclipse_eval.frag: the inputs only

struct Sample {
    float a, s;
    double reference;
    int set;  // 0: Sun-Moon, 1: Earth from the Moon
};

struct Stats {
    double max = 0.0, sum = 0.0;
    long n = 0;
    void add(double e) { max = std::max(max, e), sum += e, ++n; }
    double mean() const { return n ? sum / n : 0.0; }
};

// A program holding one mode's code only (ECLIPSE_EVAL_MODE; -1: every mode, for the errors).
std::unique_ptr<GlProgram> build_program(int mode) {
    return std::make_unique<GlProgram>("tests/fullscreen.vert", "tests/eclipse_eval.frag",
                                       "#define ECLIPSE_EVAL_MODE " + std::to_string(mode) + "\n");
}

void set_uniforms(GLuint p, const glm::vec2& lut_size, float limb_u, float order) {
    glUseProgram(p);
    glUniform1i(glGetUniformLocation(p, "u_params"), 0);
    glUniform1i(glGetUniformLocation(p, "u_lut"), 1);
    glUniform2f(glGetUniformLocation(p, "u_lut_size"), lut_size.x, lut_size.y);
    glUniform1f(glGetUniformLocation(p, "u_limb_u"), limb_u);
    glUniform1f(glGetUniformLocation(p, "u_order"), order);
    const GLint m = glGetUniformLocation(p, "u_mode");
    if (m >= 0) glUniform1i(m, -1);
}

// Median ms per frame of each program; the programs take turns frame by frame, so drifts of the
// shared machine (other processes, clock) hit every mode alike.
struct Timing {
    double median, p25, p75;
};
std::vector<Timing> frame_ms(const std::vector<GLuint>& programs, int reps) {
    for (GLuint p : programs) {  // warm-up: compilation on first use, caches
        glUseProgram(p);
        for (int i = 0; i < 2; ++i) glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glFinish();
    std::vector<std::vector<double>> ms(programs.size());
    for (int r = 0; r < reps; ++r)
        for (size_t k = 0; k < programs.size(); ++k) {
            glUseProgram(programs[k]);
            const auto t0 = std::chrono::steady_clock::now();
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glFinish();
            ms[k].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
    std::vector<Timing> out;
    for (auto& v : ms) {
        std::sort(v.begin(), v.end());
        out.push_back({v[v.size() / 2], v[v.size() / 4], v[(3 * v.size()) / 4]});
    }
    return out;
}

// Reference values on all cores.
void fill_reference(std::vector<Sample>& samples, double u) {
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i; (i = next.fetch_add(256)) < samples.size();)
            for (size_t k = i; k < std::min(samples.size(), i + 256); ++k)
                samples[k].reference = eclipse::visible_fraction_reference(samples[k].a, samples[k].s, u);
    };
    std::vector<std::thread> threads;
    for (unsigned k = 1; k < std::max(1u, std::thread::hardware_concurrency()); ++k) threads.emplace_back(work);
    work();
    for (auto& t : threads) t.join();
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"eclipse shadow modes: speed vs error"};
    int size = 1024, reps = 15;
    double limb_u = 0.6, order = 4.0;
    std::string csv;
    app.add_option("--size", size, "frame width and height in pixels")->check(CLI::Range(16, 8192));
    app.add_option("--reps", reps, "timed frames per mode (median reported)")->check(CLI::Range(1, 1000));
    app.add_option("--limb-u", limb_u, "the Sun's linear limb-darkening coefficient")->check(CLI::Range(0.0, 1.0));
    app.add_option("--order", order, "fast mode: Butterworth order n")->check(CLI::Range(0.5, 64.0));
    app.add_option("--csv", csv, "also write the figures as CSV");
    CLI11_PARSE(app, argc, argv);
    spdlog::set_level(spdlog::level::warn);
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    const float u = static_cast<float>(limb_u), n_order = static_cast<float>(order);

    EglContext gl(-1);
    std::printf("renderer: %s\n", gl.info().renderer.c_str());

    // The default table (its build time is in the LUT-size table below).
    const sh::Texture2DData lut =
        eclipse::build_eclipse_lut(limb_u, eclipse::kEclipseLutWidth, eclipse::kEclipseLutHeight);
    const glm::vec2 lut_size(lut.width, lut.height);
    const GlTexture lut_tex(lut.width, lut.height, lut.texels.data(), GL_LINEAR);
    GlEmptyVertexArray vao;
    vao.bind();

    // --- speed -------------------------------------------------------------------------------
    std::vector<glm::vec4> params(static_cast<size_t>(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float a = 0.9f + 0.2f * (x + 0.5f) / size;
            params[static_cast<size_t>(y) * size + x] = glm::vec4(a, (1.0f + a) * (y + 0.5f) / size, 0.0f, 1.0f);
        }
    const GlTexture param_tex(size, size, params.data(), GL_NEAREST);
    GlFramebuffer fb(size, size);
    fb.bind();
    param_tex.bind(0);
    lut_tex.bind(1);
    struct Mode {
        const char* name;
        int id;
        double ms = 0.0, p25 = 0.0, p75 = 0.0;
    };
    std::vector<Mode> modes = {{"none", kModeNone},
                               {"exact", sh::ECLIPSE_MODE_EXACT},
                               {"fast", sh::ECLIPSE_MODE_FAST},
                               {"lut", sh::ECLIPSE_MODE_LUT},
                               {"illustrative", sh::ECLIPSE_MODE_ILLUSTRATIVE}};
    std::vector<std::unique_ptr<GlProgram>> owned;
    std::vector<GLuint> programs;
    for (auto& m : modes) {
        owned.push_back(build_program(m.id));
        programs.push_back(owned.back()->id());
        set_uniforms(programs.back(), lut_size, u, n_order);
    }
    const std::vector<Timing> ms = frame_ms(programs, reps);
    for (size_t k = 0; k < modes.size(); ++k) {
        modes[k].ms = ms[k].median;
        modes[k].p25 = ms[k].p25;
        modes[k].p75 = ms[k].p75;
    }
    gl::check("timed passes");
    const double base_ms = modes[0].ms;
    const double pixels = static_cast<double>(size) * size;

    // --- error (of what the GPU computes) -------------------------------------------------------
    std::vector<Sample> samples;
    for (int i = 0; i <= 200; ++i) {
        const double a = 0.9 + 0.2 * i / 200;
        for (int k = 0; k < 401; ++k)
            samples.push_back({static_cast<float>(a),
                               static_cast<float>(std::fabs(1.0 - a) + 2.0 * std::min(1.0, a) * k / 401), 0.0, 0});
    }
    for (int k = 0; k < 4001; ++k) samples.push_back({3.7f, static_cast<float>(2.7 + 2.0 * k / 4001), 0.0, 1});
    const auto t_ref = std::chrono::steady_clock::now();
    fill_reference(samples, limb_u);
    const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_ref).count();
    const int ew = 512, eh = static_cast<int>((samples.size() + ew - 1) / ew);
    std::vector<glm::vec4> eparams(static_cast<size_t>(ew) * eh, glm::vec4(1.0f, 3.0f, 0.0f, 1.0f));
    for (size_t i = 0; i < samples.size(); ++i) eparams[i] = glm::vec4(samples[i].a, samples[i].s, 0.0f, 1.0f);
    const GlTexture eparam_tex(ew, eh, eparams.data(), GL_NEAREST);
    GlFramebuffer efb(ew, eh);
    efb.bind();
    eparam_tex.bind(0);
    lut_tex.bind(1);
    const auto all = build_program(-1);
    set_uniforms(all->id(), lut_size, u, n_order);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const Image img = efb.read();  // row 0 = top = texture row eh - 1
    Stats err[3][2];               // exact, fast, lut x Sun-Moon, Earth-Moon
    for (size_t i = 0; i < samples.size(); ++i) {
        const int x = static_cast<int>(i % ew), y = static_cast<int>(i / ew);
        const float* g = img.pixel(x, eh - 1 - y);
        for (int m = 0; m < 3; ++m) err[m][samples[i].set].add(std::fabs(g[m] - samples[i].reference));
    }

    // --- LUT size: build time, memory, error (C++ lookup) -------------------------------------
    struct LutRow {
        int w, h;
        double build_ms, kib;
        Stats e[2];
    };
    std::vector<LutRow> lut_rows;
    for (auto [w, h] : {std::pair{17, 17}, {33, 17}, {33, 33}, {65, 33}, {65, 65}, {129, 65}, {129, 129}, {257, 257}}) {
        LutRow r{w, h, 0.0, w * h * 16.0 / 1024.0, {}};
        const double u_fresh = limb_u + 1e-12 * (w + h);  // a key the memo has not seen: time a real build
        const auto t0 = std::chrono::steady_clock::now();
        const sh::Texture2DData t = eclipse::build_eclipse_lut(std::min(u_fresh, 1.0), w, h);
        r.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        const sh::sampler2D smp{&t};
        for (const Sample& s : samples)
            r.e[s.set].add(std::fabs(sh::eclipse_visible_lut(smp, sh::vec2(w, h), s.a, s.s) - s.reference));
        lut_rows.push_back(r);
    }

    // --- report ---------------------------------------------------------------------------------
    std::printf(
        "\n%dx%d frame, median of %d; baseline (\"none\": fetch and write) %.2f ms; reference for %zu samples: %.1f "
        "s\n\n",
        size, size, reps, base_ms, samples.size(), ref_s);
    std::printf(
        "| mode | ms/frame (p25-p75) | pass ms (minus none) | ns/pixel | Sun-Moon max err | Sun-Moon mean err | a=3.7 "
        "max err | a=3.7 mean err |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    auto fmt = [](double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%.2e", v);
        return std::string(b);
    };
    for (const auto& m : modes) {
        const int k = m.id == sh::ECLIPSE_MODE_EXACT  ? 0
                      : m.id == sh::ECLIPSE_MODE_FAST ? 1
                      : m.id == sh::ECLIPSE_MODE_LUT  ? 2
                                                      : -1;
        const double pass = m.ms - base_ms;
        std::printf("| %s | %.2f (%.2f-%.2f) | %.2f | %.2f | %s | %s | %s | %s |\n", m.name, m.ms, m.p25, m.p75, pass,
                    pass * 1e6 / pixels, k < 0 ? "n/a" : fmt(err[k][0].max).c_str(),
                    k < 0 ? "n/a" : fmt(err[k][0].mean()).c_str(), k < 0 ? "n/a" : fmt(err[k][1].max).c_str(),
                    k < 0 ? "n/a" : fmt(err[k][1].mean()).c_str());
    }
    std::printf(
        "\n| LUT size | KiB (RGBA32F) | build ms | Sun-Moon max err | Sun-Moon mean err | a=3.7 max err | a=3.7 mean "
        "err |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const auto& r : lut_rows)
        std::printf("| %dx%d%s | %.0f | %.1f | %s | %s | %s | %s |\n", r.w, r.h,
                    r.w == eclipse::kEclipseLutWidth && r.h == eclipse::kEclipseLutHeight ? " (default)" : "", r.kib,
                    r.build_ms, fmt(r.e[0].max).c_str(), fmt(r.e[0].mean()).c_str(), fmt(r.e[1].max).c_str(),
                    fmt(r.e[1].mean()).c_str());
    if (!csv.empty()) {
        std::ofstream out(csv);
        out << "kind,name,ms_frame,ms_p25,ms_p75,ms_pass,ns_per_pixel,build_ms,kib,sun_moon_max,sun_moon_mean,earth_"
               "moon_max,earth_moon_mean\n";
        for (const auto& m : modes) {
            const int k = m.id == sh::ECLIPSE_MODE_EXACT  ? 0
                          : m.id == sh::ECLIPSE_MODE_FAST ? 1
                          : m.id == sh::ECLIPSE_MODE_LUT  ? 2
                                                          : -1;
            const double pass = m.ms - base_ms;
            out << "mode," << m.name << "," << m.ms << "," << m.p25 << "," << m.p75 << "," << pass << ","
                << pass * 1e6 / pixels << ",,,";
            if (k < 0)
                out << ",,,\n";
            else
                out << err[k][0].max << "," << err[k][0].mean() << "," << err[k][1].max << "," << err[k][1].mean()
                    << "\n";
        }
        for (const auto& r : lut_rows)
            out << "lut_size," << r.w << "x" << r.h << ",,,,,," << r.build_ms << "," << r.kib << "," << r.e[0].max
                << "," << r.e[0].mean() << "," << r.e[1].max << "," << r.e[1].mean() << "\n";
    }
    return 0;
}
