#include "passes/star_sky_weights.hpp"

#include <algorithm>
#include <cmath>

#include "passes/atmosphere_uniforms.hpp"
#include "passes/sky_view_gpu.hpp"

namespace cupola {

namespace {
int rows_for(size_t stars) {
    return std::max(1, static_cast<int>((stars + StarSkyWeights::kWidth - 1) / StarSkyWeights::kWidth));
}

// The stars as texels; the texels past the last star hold the zenith at magnitude 0 (never read).
std::vector<glm::vec4> star_texels(const std::vector<glm::vec4>& stars) {
    std::vector<glm::vec4> t(static_cast<size_t>(StarSkyWeights::kWidth * rows_for(stars.size())),
                             glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
    std::copy(stars.begin(), stars.end(), t.begin());
    return t;
}
}  // namespace

StarSkyWeights::StarSkyWeights(const std::vector<glm::vec4>& stars)
    : stars_(kWidth, rows_for(stars.size()), star_texels(stars).data(), GL_NEAREST),
      weights_(kWidth, rows_for(stars.size()), nullptr, GL_NEAREST),
      fbo_({&weights_}),
      program_("fullscreen.vert", "star_weights.frag") {
    glCreateBuffers(1, &buffer_);
    const std::vector<float> ones(static_cast<size_t>(weights_.width() * weights_.height()) * 4, 1.0f);
    glNamedBufferData(buffer_, static_cast<GLsizeiptr>(ones.size() * sizeof(float)), ones.data(), GL_DYNAMIC_COPY);
    glCreateBuffers(1, &draw_command_);
    const GLuint none[4] = {0, 1, 0, 0};
    glNamedBufferData(draw_command_, sizeof none, none, GL_DYNAMIC_COPY);
}

StarSkyWeights::~StarSkyWeights() {
    glDeleteBuffers(1, &draw_command_);
    glDeleteBuffers(1, &buffer_);
}

glm::vec3 StarSkyWeights::on_grid(const glm::vec3& unit) {
    constexpr float kGrid = 16384.0f;  // 2^14
    const glm::vec3 r(std::round(unit.x * kGrid), std::round(unit.y * kGrid), std::round(unit.z * kGrid));
    return glm::normalize(r / kGrid);
}

bool StarSkyWeights::update(const StarSky& sky, int star_count) {
    const glm::vec3 c = on_grid(sky.center_dir_world), s = on_grid(sky.sun_world), m = on_grid(sky.moon_world);
    const float moon_ratio = sky.moon_table ? sky.moon_ratio : 0.0f;
    const std::array<float, 16> key{sky.table_in.x,
                                    sky.table_in.y,
                                    c.x,
                                    c.y,
                                    c.z,
                                    s.x,
                                    s.y,
                                    s.z,
                                    sky.to_cd_m2,
                                    static_cast<float>(star_count),
                                    sky.moon_mu,
                                    m.x,
                                    m.y,
                                    m.z,
                                    moon_ratio,
                                    sky.night_sky_cd_m2};
    if (valid_ && key == key_) return false;
    const DrawTargetRestorer restore;
    fbo_.bind();
    glDisable(GL_BLEND);
    program_.use();
    set_uniforms(sky, c, s, star_count);
    set_moon_uniforms(sky, m);
    const GLuint none[4] = {0, 1, 0, 0};
    glNamedBufferSubData(draw_command_, 0, sizeof none, none);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, draw_command_);
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT);  // the star draw reads the command this wrote
    // Into the attribute buffer, on the GPU: the texels, row by row.
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer_);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(weights_.id(), 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(weights_.width() * weights_.height() * 4 * sizeof(float)), nullptr);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl::check("star sky weights");
    key_ = key;
    valid_ = true;
    ++renders_;
    return true;
}

void StarSkyWeights::set_uniforms(const StarSky& sky, const glm::vec3& center_dir, const glm::vec3& sun,
                                  int star_count) {
    program_.set("u_star_count", star_count);
    program_.set("u_width", kWidth);
    stars_.bind(0);
    program_.set("u_stars", 0);
    sky.table->bind(1);
    program_.set("u_sky_phased", 1);
    program_.set("u_sky_mie", 2);
    program_.set("u_sky_third", 3);
    program_.set("u_sky_size", sky.table->size());
    set_atmosphere_params(program_, sky.params);
    program_.set("u_sky_d_m", sky.table_in.x);
    program_.set("u_sky_center_dir", center_dir);
    program_.set("u_sky_sun", sun);
    program_.set("u_sky_to_cd_m2", sky.to_cd_m2);
    program_.set("u_night_sky_cd_m2", sky.night_sky_cd_m2);
}

void StarSkyWeights::set_moon_uniforms(const StarSky& sky, const glm::vec3& moon) {
    program_.set("u_moon_ratio", sky.moon_table ? sky.moon_ratio : 0.0f);
    if (!sky.moon_table) return;
    sky.moon_table->bind(4);
    program_.set("u_moon_phased", 4);
    program_.set("u_moon_mie", 5);
    program_.set("u_moon_third", 6);
    program_.set("u_moon", moon);
}

}  // namespace cupola
