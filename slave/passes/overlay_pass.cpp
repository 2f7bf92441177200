#include "passes/overlay_pass.hpp"

#include <algorithm>
#include <cmath>

#include "image/mip_chain.hpp"
#include "overlay/constellation_figures.hpp"
#include "overlay/label_declutter.hpp"
#include "overlay/overlay_lines.hpp"
#include "passes/sphere_billboard.hpp"
#include "passes/text_raster.hpp"

namespace cupola {

namespace {

constexpr int kAtlasPx = 48;  // em height the glyphs are rasterized at
constexpr int kAtlasWidth = 2048;
constexpr int kAtlasPad = 3;           // texels between labels (their mipmaps do not bleed into each other)
constexpr double kBesideGap_em = 0.6;  // a star's or body's name starts this far right of it
constexpr int kArcsPerChunk = 16;      // arcs culled together against the channel
static_assert(kOverlayCount == 10, "shaders/overlay_line.vert and overlay_label.vert: kOverlays");
constexpr double kCullSlack_rad = 0.02;  // more than any line's half width and margin

// An arc's quad: vertices (dir, pole, lat, side, overlay) at a and b on either edge, and two
// triangles' indices. An arc that continues the previous one along the same circle shares its two
// vertices at the joint, so a tessellated circle costs two vertices an arc, not six.
struct ArcMesh {
    std::vector<float> vertices;
    std::vector<GLuint> indices;
    GLuint count = 0;
    const SkyArc* last = nullptr;
    float overlay = 0.0f;  // the overlay the arcs added now belong to

    void begin_overlay(size_t k) {
        overlay = static_cast<float>(k);
        last = nullptr;  // no arc continues one of another overlay
    }
    void vertex(const SkyArc& arc, const glm::dvec3& d, float side) {
        vertices.insert(vertices.end(),
                        {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z),
                         static_cast<float>(arc.pole.x), static_cast<float>(arc.pole.y), static_cast<float>(arc.pole.z),
                         static_cast<float>(arc.lat_rad), side, overlay});
        ++count;
    }
    void add(const SkyArc& arc) {
        const bool continues = last && last->b == arc.a && last->pole == arc.pole && last->lat_rad == arc.lat_rad;
        if (!continues) vertex(arc, arc.a, -1.0f), vertex(arc, arc.a, 1.0f);
        const GLuint a_minus = count - 2, a_plus = count - 1;
        vertex(arc, arc.b, -1.0f), vertex(arc, arc.b, 1.0f);
        indices.insert(indices.end(), {a_minus, a_plus, count - 2, count - 2, a_plus, count - 1});
        last = &arc;
    }
};

// A shelf packer over an atlas kAtlasWidth wide: every label has the face's line height.
struct Shelf {
    int x = kAtlasPad, y = kAtlasPad, row_height = 0;
    glm::ivec2 place(int w, int h) {
        if (x + w + kAtlasPad > kAtlasWidth) {
            x = kAtlasPad;
            y += row_height + kAtlasPad;
        }
        row_height = std::max(row_height, h);
        const glm::ivec2 at(x, y);
        x += w + kAtlasPad;
        return at;
    }
};

// The atlas's full mipmap chain, level 0 first, in 8 bits: built on the CPU (image/mip_chain.hpp
// says why), a tenth of what glGenerateTextureMipmap costs on llvmpipe.
std::vector<std::vector<uint8_t>> coverage_levels(int width, int height, const std::vector<float>& coverage) {
    const auto unorm8 = [](const std::vector<float>& v) {
        std::vector<uint8_t> out(v.size());
        for (size_t i = 0; i < v.size(); ++i)
            out[i] = static_cast<uint8_t>(std::lround(std::clamp(v[i], 0.0f, 1.0f) * 255.0f));
        return out;
    };
    std::vector<std::vector<uint8_t>> levels{unorm8(coverage)};
    for (const MipLevel& l : box_filter_mip_chain(width, height, coverage, 1)) levels.push_back(unorm8(l.texels));
    return levels;
}

}  // namespace

OverlayPass::OverlayPass(const SceneConfig& scene, const std::vector<Star>& stars)
    : scene_(&scene),
      line_program_("overlay_line.vert", "overlay_line.frag"),
      label_program_("overlay_label.vert", "overlay_label.frag"),
      static_labels_({3, 2, 2, 1}),
      body_labels_({3, 2, 2, 1}) {
    const std::vector<ConstellationFigure> figures = load_constellation_figures(scene.overlays.figures);
    build_lines(figures);
    build_labels(figures, stars);
}

void OverlayPass::build_lines(const std::vector<ConstellationFigure>& figures) {
    const auto arcs = overlay_lines(figures);
    ArcMesh mesh;
    int first = 0;  // the overlay's first arc in the one buffer
    for (size_t k = 0; k < kOverlayCount; ++k) {
        arcs_[k] = arcs[k].size();
        chunks_[k] = arc_chunks(arcs[k], kArcsPerChunk);
        for (ArcChunk& c : chunks_[k]) c.first_arc += first;
        mesh.begin_overlay(k);
        for (const SkyArc& a : arcs[k]) {
            mesh.add(a);
            arc_cones_.emplace_back(arc_cone(a));
        }
        first += static_cast<int>(arcs[k].size());
    }
    if (mesh.indices.empty()) return;
    lines_ = std::make_unique<GlVertexBuffer>(std::vector<int>{3, 3, 1, 1, 1});
    lines_->upload(mesh.vertices);
    lines_->upload_indices(mesh.indices);
}

// Every label rasterized once (FreeType) into one atlas; each gets its quad in em units of its
// overlay's text size.
void OverlayPass::build_labels(const std::vector<ConstellationFigure>& figures, const std::vector<Star>& stars) {
    labels_ = overlay_labels(figures, *scene_, stars);
    const TextFace face(kAtlasPx);
    std::vector<TextRaster> rasters;
    std::vector<glm::ivec2> at;
    Shelf shelf;
    for (const OverlayLabel& l : labels_) {
        rasters.push_back(face.raster(l.text));
        at.push_back(shelf.place(rasters.back().width, rasters.back().height));
    }
    const int height = std::max(1, shelf.y + shelf.row_height + kAtlasPad);
    std::vector<float> texels(static_cast<size_t>(kAtlasWidth) * height, 0.0f);
    for (size_t i = 0; i < labels_.size(); ++i) {
        const TextRaster& r = rasters[i];
        for (int y = 0; y < r.height; ++y)
            for (int x = 0; x < r.width; ++x)
                texels[static_cast<size_t>(at[i].y + y) * kAtlasWidth + at[i].x + x] = r.at(x, y);
        const double em = glm::radians(scene_->overlays.styles[static_cast<size_t>(labels_[i].kind)].text_deg);
        const float w = static_cast<float>(em * r.width / kAtlasPx), h = static_cast<float>(em * r.height / kAtlasPx);
        const float x0 =
            labels_[i].placement == LabelPlacement::Beside ? static_cast<float>(kBesideGap_em * em) : -0.5f * w;
        LabelBox box;
        box.corners = glm::vec4(x0, -0.5f * h, x0 + w, 0.5f * h);
        // Raster row 0 (the top of the text) is atlas row at.y: texture t = row / height.
        box.uv = glm::vec4(static_cast<float>(at[i].x) / kAtlasWidth, static_cast<float>(at[i].y + r.height) / height,
                           static_cast<float>(at[i].x + r.width) / kAtlasWidth, static_cast<float>(at[i].y) / height);
        boxes_.push_back(box);
    }
    atlas_ = std::make_unique<GlTexture>(kAtlasWidth, height, coverage_levels(kAtlasWidth, height, texels));
    upload_static_labels();
}

std::vector<float> OverlayPass::label_vertices(const LabelBox& b, const glm::dvec3& anchor, size_t kind) {
    std::vector<float> v;
    const auto vertex = [&](float x, float y, float u, float t) {
        v.insert(v.end(), {static_cast<float>(anchor.x), static_cast<float>(anchor.y), static_cast<float>(anchor.z), x,
                           y, u, t, static_cast<float>(kind)});
    };
    const glm::vec4 c = b.corners, uv = b.uv;
    vertex(c.x, c.y, uv.x, uv.y), vertex(c.z, c.y, uv.z, uv.y), vertex(c.x, c.w, uv.x, uv.w);
    vertex(c.x, c.w, uv.x, uv.w), vertex(c.z, c.y, uv.z, uv.y), vertex(c.z, c.w, uv.z, uv.w);
    return v;
}

// The labels that stay put in their overlay's frame, in one buffer in the labels' order.
void OverlayPass::upload_static_labels() {
    std::vector<float> v;
    constexpr size_t kFloatsPerVertex = 8;
    for (size_t i = 0; i < labels_.size(); ++i) {
        label_vertex_first_.push_back(labels_[i].body ? -1 : static_cast<GLint>(v.size() / kFloatsPerVertex));
        if (labels_[i].body) continue;
        const auto q = label_vertices(boxes_[i], labels_[i].anchor, static_cast<size_t>(labels_[i].kind));
        v.insert(v.end(), q.begin(), q.end());
    }
    static_labels_.upload(v);
}

std::optional<glm::dvec3> OverlayPass::label_direction(size_t i) const {
    const OverlayLabel& l = labels_[i];
    if (!shown_[static_cast<size_t>(l.kind)]) return std::nullopt;
    if (!l.body) return *frames_.to_world(overlay_frame_of(l.kind)) * l.anchor;  // shown: it has its frame
    const Snapshot& s = *frame_->snap;
    if (*l.body >= s.bodies.size() || (frames_.ground_body && *frames_.ground_body == *l.body)) return std::nullopt;
    const glm::dvec3 to = s.bodies[*l.body].position_m - s.camera_position_m;
    if (!(glm::length(to) > 0.0)) return std::nullopt;
    return glm::normalize(to);
}

// Which labels this frame draws: those of the shown overlays, no two overlapping, the cardinal
// points first, then the bodies, the named stars and the constellations' names.
void OverlayPass::declutter() {
    std::vector<LabelFootprint> footprints;
    std::vector<size_t> index;
    label_dirs_.assign(labels_.size(), std::nullopt);
    for (size_t i = 0; i < labels_.size(); ++i) {
        const auto d = label_dirs_[i] = label_direction(i);
        if (!d) continue;
        const OverlayLabel& l = labels_[i];
        const int priority = l.kind == OverlayKind::Cardinals            ? kCardinalPriority
                             : l.body                                    ? kBodyPriority
                             : l.kind == OverlayKind::ConstellationNames ? kConstellationPriority
                                                                         : kStarPriority;
        footprints.push_back({*d, glm::dvec4(boxes_[i].corners), priority});
        index.push_back(i);
    }
    const std::vector<bool> kept = declutter_labels(footprints, frames_.label_up_world);
    label_drawn_.assign(labels_.size(), false);
    for (size_t k = 0; k < index.size(); ++k) label_drawn_[index[k]] = kept[k];
}

// The drawn bodies' names at their directions from the camera this frame (declutter's).
void OverlayPass::update_body_labels() {
    std::vector<float> v;
    for (size_t i = 0; i < labels_.size(); ++i) {
        if (!labels_[i].body || !label_drawn_[i]) continue;
        const auto q = label_vertices(boxes_[i], *label_dirs_[i], static_cast<size_t>(OverlayKind::Labels));
        v.insert(v.end(), q.begin(), q.end());
    }
    body_labels_.upload(v);
}

int OverlayPass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    const auto& alpha = frame.snap->settings.overlay_alpha;
    if (std::all_of(alpha.begin(), alpha.end(), [](float a) { return a <= 0.0f; })) return 0;
    frames_ = overlay_frames(*frame.snap, *scene_);
    pixel_rad_ = static_cast<float>(pixel_angle_rad(*frame.view.frustum));
    return 1;
}

glm::vec4 OverlayPass::color_of(size_t k) const {
    const float exposure = std::max(frame_->snap->settings.exposure, 1e-30f);
    return glm::vec4(glm::vec3(scene_->overlays.styles[k].color) / exposure, frame_->snap->settings.overlay_alpha[k]);
}

void OverlayPass::draw(const PassInputs&, int) {
    if (!set_overlay_uniforms()) return;
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // over; coverage stays
    draw_lines();
    draw_labels();  // over every line
    glDisablei(GL_BLEND, 0);
    gl::check("overlay pass");
}

bool OverlayPass::set_overlay_uniforms() {
    std::array<glm::vec4, kOverlayCount> colors{}, line_style{};
    for (size_t k = 0; k < kOverlayCount; ++k) {
        const auto frame_to_world = frames_.to_world(overlay_frame_of(static_cast<OverlayKind>(k)));
        // The horizon's overlays have no frame away from any ground.
        shown_[k] = frame_->snap->settings.overlay_alpha[k] > 0.0f && frame_to_world.has_value();
        to_channel_[k] = shown_[k] ? glm::mat3(frame_->view.world_to_channel * *frame_to_world) : glm::mat3(1.0f);
        colors[k] = color_of(k);
        line_style[k].x = static_cast<float>(0.5 * glm::radians(scene_->overlays.styles[k].width_deg));
    }
    if (std::none_of(shown_.begin(), shown_.end(), [](bool b) { return b; })) return false;
    const glm::mat4 projection(frame_->view.frustum->projection(0.1, 10.0));
    for (const GlProgram* p : {&line_program_, &label_program_}) {
        p->use();
        p->set("u_projection", projection);
        p->set("u_to_channel", to_channel_.data(), static_cast<int>(kOverlayCount));
        p->set("u_color", colors.data(), static_cast<int>(kOverlayCount));
    }
    line_program_.use();
    line_program_.set("u_line", line_style.data(), static_cast<int>(kOverlayCount));
    // Room for the ramp, which reaches half of fwidth(s) past the edge: fwidth is |ds/dx| + |ds/dy|, up
    // to sqrt(2) pixels' angle for a diagonal line (at the widest pixel); and the chord's sag below
    // an arc of the longest step.
    line_program_.set("u_margin_rad", 0.75f * pixel_rad_ + 1.6e-4f);
    label_program_.use();
    label_program_.set("u_up", glm::vec3(frame_->view.world_to_channel * frames_.label_up_world));
    return true;
}

// Every shown overlay's arcs that can touch the channel, in one draw: the chunks first, then the
// arcs of those that touch it one by one (a CPU rasteriser pays for every triangle it is given).
void OverlayPass::draw_lines() {
    if (!lines_) return;
    offsets_.clear();
    counts_.clear();
    const FrustumSides sides(frame_->view.tangents());
    for (size_t k = 0; k < kOverlayCount; ++k) {
        if (!shown_[k]) continue;
        for (const ArcChunk& c : chunks_[k])
            if (sides.touched_by(glm::dvec3(to_channel_[k] * glm::vec3(c.centre)), c.radius_rad + kCullSlack_rad))
                add_visible_arcs(c, to_channel_[k], sides);
    }
    if (counts_.empty()) return;
    line_program_.use();
    lines_->bind();
    glMultiDrawElements(GL_TRIANGLES, counts_.data(), GL_UNSIGNED_INT, offsets_.data(),
                        static_cast<GLsizei>(counts_.size()));
}

void OverlayPass::add_visible_arcs(const ArcChunk& c, const glm::mat3& to_channel, const FrustumSides& sides) {
    for (int i = c.first_arc; i < c.first_arc + c.arc_count; ++i) {
        const glm::vec4& cone = arc_cones_[static_cast<size_t>(i)];
        if (!sides.touched_by(glm::dvec3(to_channel * glm::vec3(cone)), cone.w + kCullSlack_rad)) continue;
        const size_t first_index = 6 * static_cast<size_t>(i);
        if (!counts_.empty() && next_index_ == first_index) {
            counts_.back() += 6;  // arcs next to each other in the buffer: one run
        } else {
            offsets_.push_back(reinterpret_cast<const void*>(first_index * sizeof(GLuint)));
            counts_.push_back(6);
        }
        next_index_ = first_index + 6;
        ++arcs_drawn_;
    }
}

// The drawn labels: the fixed ones in one draw (runs of neighbours in the buffer), then the
// bodies' (placed this frame).
void OverlayPass::draw_labels() {
    declutter();
    run_first_.clear();
    run_count_.clear();
    for (size_t i = 0; i < labels_.size(); ++i) {
        if (!label_drawn_[i] || label_vertex_first_[i] < 0) continue;
        if (!run_first_.empty() && run_first_.back() + run_count_.back() == label_vertex_first_[i])
            run_count_.back() += 6;
        else
            run_first_.push_back(label_vertex_first_[i]), run_count_.push_back(6);
    }
    const bool bodies = shown_[static_cast<size_t>(OverlayKind::Labels)];
    if (bodies) update_body_labels();  // only in frames that show them
    if (run_first_.empty() && !(bodies && body_labels_.vertex_count() > 0)) return;
    label_program_.use();
    atlas_->bind(0);
    label_program_.set("u_atlas", 0);
    if (!run_first_.empty()) {
        static_labels_.bind();
        glMultiDrawArrays(GL_TRIANGLES, run_first_.data(), run_count_.data(), static_cast<GLsizei>(run_first_.size()));
    }
    if (bodies && body_labels_.vertex_count() > 0) {
        body_labels_.bind();
        glDrawArrays(GL_TRIANGLES, 0, body_labels_.vertex_count());
    }
}

}  // namespace cupola
