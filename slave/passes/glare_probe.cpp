#include "passes/glare_probe.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "glare/glare_frame.hpp"
#include "passes/sphere_billboard.hpp"
#include "projection/dome_frame.hpp"
#include "scene/snapshot_bodies.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {
constexpr int kSets = 3;  // query sets in flight at most
constexpr int kQueriesPerSource = 1 + GlareMeasurement::kWedges;
constexpr double kProbeMargin = 1.15;  // probe half-width / disc radius (tangents)
}  // namespace

struct GlareProbe::Set {
    struct Item {
        uint16_t body;
        uint32_t star;
        double pixel_sr;  // solid angle of one probe pixel over the disc
    };
    std::vector<GLuint> queries;  // kQueriesPerSource per item: total, then the wedges
    std::vector<Item> items;
    uint64_t frame = 0;
    bool pending = false;
    uint64_t issued = 0;  // order of issue
};

GlareProbe::GlareProbe(const ClusterConfig& cluster, const ChannelConfig& channel, const SceneConfig& scene,
                       BodyPass& bodies, const EclipseShadowUniforms& shadows)
    : size_(scene.glare.probe_size),
      camera_from_dome_(dome_tilt_rotation(cluster.dome.tilt_deg)),
      scene_(&scene),
      bodies_(bodies),
      shadows_(shadows),
      target_(scene.glare.probe_size, scene.glare.probe_size),
      query_("fullscreen.vert", "glare_query.frag") {
    if (static_cast<int>(cluster.channels.size()) > kMaxChannels)
        throw std::runtime_error("glare: at most " + std::to_string(kMaxChannels) +
                                 " channels can share glare visibility (the cluster has " +
                                 std::to_string(cluster.channels.size()) + ")");
    own_frustum_only_ = scene.glare.visibility == GlareVisibilityMode::PerChannel;
    for (size_t i = 0; i < cluster.channels.size(); ++i) {
        const ChannelConfig& c = cluster.channels[i];
        if (c.id == channel.id) self_ = static_cast<int>(i);
        channel_from_camera_.push_back(glm::transpose(camera_from_dome_ * channel_rotation(c.orientation)));
        const ChannelFrustum f = c.frustum();
        channel_tangents_.push_back(glm::vec4(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up()));
        frusta_.push_back(f);
    }
    glCreateVertexArrays(1, &vao_);
    const int max_sources = scene.glare.max_sources;
    for (int s = 0; s < kSets; ++s) {
        auto set = std::make_unique<Set>();
        set->queries.resize(static_cast<size_t>(max_sources * kQueriesPerSource));
        glGenQueries(static_cast<GLsizei>(set->queries.size()), set->queries.data());
        sets_.push_back(std::move(set));
    }
    gl::check("glare probe creation");
}

GlareProbe::~GlareProbe() {
    for (auto& s : sets_) glDeleteQueries(static_cast<GLsizei>(s->queries.size()), s->queries.data());
    glDeleteVertexArrays(1, &vao_);
    if (counts_.sets_dropped_late > 0)
        spdlog::warn("glare probe: {} of {} query sets were still running when needed again and were dropped",
                     counts_.sets_dropped_late, counts_.sets_issued);
}

int GlareProbe::prepare(const FrameContext& frame) {
    frame_ = &frame;
    return frame.snap->glare.empty() || !measuring_ ? 0 : 1;
}

void GlareProbe::draw(const PassInputs&, int) { measure(*frame_->snap, bodies_, frame_->light, shadows_); }

// The probe's view of one source: looking at it, axes of the glare frame. Not copied: the
// channel view points at the frustum.
struct GlareProbe::View {
    View(const Snapshot& snap, const GlareFrame& frame, double radius_rad, int size)
        : radius(radius_rad), t(kProbeMargin * std::tan(radius_rad)), frustum(probe_frustum(t, size)) {
        view.frustum = &frustum;
        view.channel_to_world = glm::dmat3(frame.right, frame.up, -frame.center);
        view.world_to_channel = glm::transpose(view.channel_to_world);
        view.camera_position_m = snap.camera_position_m;
    }
    View(const View&) = delete;
    View& operator=(const View&) = delete;

    static ChannelFrustum probe_frustum(double t, int size) {
        const double half_deg = glm::degrees(std::atan(t));
        return ChannelFrustum(EulerDeg{}, FovDeg{half_deg, half_deg, half_deg, half_deg}, size, size);
    }

    double radius;  // the disc's angular radius as probed
    double t;       // tangent of the view's half-width
    ChannelFrustum frustum;
    ChannelView view;
};

void GlareProbe::measure(const Snapshot& snap, BodyPass& bodies, const SunLight& light,
                         const EclipseShadowUniforms& shadows) {
    if (snap.glare.empty()) return;
    Set& set = claim_set(snap.frame);
    const glm::dmat3 world_from_camera = glm::mat3_cast(snap.camera_orientation);
    const glm::dmat3 dome_from_world = glm::transpose(camera_from_dome_) * glm::transpose(world_from_camera);
    const size_t n = std::min(snap.glare.size(), set.queries.size() / kQueriesPerSource);
    for (size_t i = 0; i < n; ++i) {
        const GlareSource& src = snap.glare[i];
        const double radius = std::max<double>(src.angular_radius, kMinRadius);
        const GlareFrame frame = glare_frame(glm::dvec3(src.direction), snap.camera_orientation);
        if (!disc_may_touch_frustum(frusta_[static_cast<size_t>(self_)], dome_from_world, frame, radius)) continue;
        const View probe(snap, frame, radius, size_);
        const double source_near_m = near_distance_m(snap, src);
        draw_occluders(snap, src, probe, source_near_m, bodies, light, shadows);  // bin 1

        // Bin 2: the queries.
        const double pixel = 2.0 * probe.t / size_;
        const double tq = 0.7 * std::tan(radius);  // typical tangent over the disc
        Set::Item item{src.body, src.star, pixel * pixel / std::pow(1.0 + tq * tq, 1.5)};
        const GLuint* q = &set.queries[set.items.size() * kQueriesPerSource];
        set.items.push_back(item);
        issue_queries(snap, src, probe, source_near_m, q);
    }
    set.pending = true;
    gl::check("glare probe");
}

GlareProbe::Set& GlareProbe::claim_set(uint64_t frame) {
    // A free slot, else the oldest set still running is given up (never waited for).
    Set* set = nullptr;
    for (auto& s : sets_)
        if (!s->pending) set = s.get();
    if (!set) {
        set = std::min_element(sets_.begin(), sets_.end(), [](const auto& a, const auto& b) {
                  return a->issued < b->issued;
              })->get();
        ++counts_.sets_dropped_late;
    }
    set->items.clear();
    set->frame = frame;
    set->issued = ++counts_.sets_issued;
    return *set;
}

// Camera to the near side of the source's body; a catalogue star (or a body the snapshot
// lacks) lies behind everything.
double GlareProbe::near_distance_m(const Snapshot& snap, const GlareSource& src) const {
    if (src.body != GlareSource::kCatalogStar)
        if (const BodyState* st = find_body(snap, src.body))
            return glm::length(st->position_m - snap.camera_position_m) - scene_->bodies[st->id].radius_m;
    return 1e300;
}

// The occluders, depth only, by true distance.
void GlareProbe::draw_occluders(const Snapshot& snap, const GlareSource& src, const View& probe, double source_near_m,
                                BodyPass& bodies, const SunLight& light, const EclipseShadowUniforms& shadows) {
    const shading::EclipseCasters no_casters = shading::eclipse_no_casters();
    target_.bind();
    target_.clear_depth(1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    for (const auto& st : snap.bodies) {
        const BodyConfig& b = scene_->bodies[st.id];
        if (b.kind == BodyKind::Star || st.id == src.body) continue;
        const SphereView sphere = make_sphere_view(probe.view, st.position_m, b.radius_m);
        if (sphere.distance_m - b.radius_m >= source_near_m) continue;  // behind the source
        if (draw_relief(st, probe)) continue;
        // Outside the probe's cone altogether?
        const double off = 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(sphere.center_dir - glm::dvec3(0, 0, -1))));
        if (!sphere.fullscreen() && off > std::atan(probe.t * 1.5) + std::asin(std::min(sphere.sin_alpha, 1.0)))
            continue;
        bodies.draw(probe.view, b, st, sphere, light, shadows, no_casters);
    }
}

bool GlareProbe::draw_relief(const BodyState& st, const View& probe) {
    if (!terrain_ || !frame_ || frame_->snap == nullptr || !terrain_->has_terrain(st.id)) return false;
    const auto it = std::find_if(frame_->far_to_near.begin(), frame_->far_to_near.end(),
                                 [&](const FrameBody& fb) { return fb.state->id == st.id; });
    if (it == frame_->far_to_near.end() || !draws_terrain(*frame_, *it)) return false;
    terrain_->draw_depth(*frame_, probe.view, *it);
    return true;
}

// The source's disc counted without depth test (the total), then with it per wedge (the visible
// part), owned by the channel whose frustum each direction falls in.
void GlareProbe::issue_queries(const Snapshot& snap, const GlareSource& src, const View& probe, double source_near_m,
                               const GLuint* q) {
    const glm::dmat3 world_from_camera = glm::mat3_cast(snap.camera_orientation);
    const ChannelView& view = probe.view;
    std::vector<glm::mat3> rot(channel_from_camera_.size());
    for (size_t k = 0; k < rot.size(); ++k)
        rot[k] = glm::mat3(channel_from_camera_[k] * glm::transpose(world_from_camera) * view.channel_to_world);
    query_.use();
    query_.set("u_tangents", view.tangents());
    query_.set("u_size", view.size());
    query_.set("u_tan_radius", static_cast<float>(std::tan(probe.radius)));
    const double depth_m = src.body != GlareSource::kCatalogStar ? source_near_m : 1e28;
    query_.set("u_depth", shading::log_depth(static_cast<float>(std::max(depth_m, 1.0))));
    query_.set("u_owner_count", static_cast<int>(rot.size()));
    query_.set("u_self", self_);
    query_.set("u_own_frustum_only", own_frustum_only_ ? 1 : 0);
    query_.set("u_owner_rot", rot.data(), static_cast<int>(rot.size()));
    query_.set("u_owner_tan", channel_tangents_.data(), static_cast<int>(channel_tangents_.size()));
    glBindVertexArray(vao_);
    glDepthMask(GL_FALSE);
    glDisable(GL_DEPTH_TEST);
    query_.set("u_wedge", -1);
    glBeginQuery(GL_SAMPLES_PASSED, q[0]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEndQuery(GL_SAMPLES_PASSED);
    glEnable(GL_DEPTH_TEST);
    for (int w = 0; w < GlareMeasurement::kWedges; ++w) {
        query_.set("u_wedge", w);
        glBeginQuery(GL_SAMPLES_PASSED, q[1 + w]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glEndQuery(GL_SAMPLES_PASSED);
    }
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
}

void GlareProbe::read(Set& set) {
    std::vector<GlareMeasurement> out;
    for (size_t i = 0; i < set.items.size(); ++i) {
        const GLuint* q = &set.queries[i * kQueriesPerSource];
        GlareMeasurement m;
        m.body = set.items[i].body;
        m.star = set.items[i].star;
        m.frame = set.frame;
        GLuint count = 0;
        glGetQueryObjectuiv(q[0], GL_QUERY_RESULT, &count);
        m.total_sr = static_cast<float>(count * set.items[i].pixel_sr);
        for (int w = 0; w < GlareMeasurement::kWedges; ++w) {
            glGetQueryObjectuiv(q[1 + w], GL_QUERY_RESULT, &count);
            m.visible_sr[w] = static_cast<float>(count * set.items[i].pixel_sr);
        }
        // Rounding must not let the parts exceed the whole (the master checks).
        const float seen = m.visible_total_sr();
        if (seen > m.total_sr) m.total_sr = seen;
        if (m.total_sr > 0.0f) out.push_back(m);
    }
    latest_ = std::move(out);
    latest_frame_ = set.frame;
    set.pending = false;
    ++counts_.sets_read;
}

bool GlareProbe::collect() {
    bool fresh = false;
    while (true) {
        Set* oldest = nullptr;
        for (auto& s : sets_)
            if (s->pending && (!oldest || s->issued < oldest->issued)) oldest = s.get();
        if (!oldest) break;
        if (!oldest->items.empty()) {
            const size_t last = oldest->items.size() * kQueriesPerSource - 1;
            GLuint available = 0;
            glGetQueryObjectuiv(oldest->queries[last], GL_QUERY_RESULT_AVAILABLE, &available);
            if (!available) break;  // later sets finish later: try again next frame
        }
        read(*oldest);
        fresh = true;
    }
    return fresh;
}

std::optional<float> GlareProbe::own_fraction(const GlareSource& source) const {
    for (const auto& m : latest_)
        if (m.body == source.body && m.star == source.star && m.total_sr > 0.0f)
            return m.visible_total_sr() / m.total_sr;
    return std::nullopt;
}

}  // namespace cupola
