#include "passes/terrain_drawer.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "passes/atmosphere_pass.hpp"
#include "passes/atmosphere_uniforms.hpp"
#include "passes/body_pass.hpp"
#include "terrain/body_relief.hpp"
#include "terrain/cluster_cut_view.hpp"

namespace cupola {

namespace {
constexpr double kNear_m = 0.05, kFar_m = 1.0e13;  // clip planes only: the depth written is logarithmic
constexpr GLuint kMapUnit = 0, kTableUnit = 1;

glm::dmat3 body_to_world(const BodyState& state) { return glm::mat3_cast(state.orientation); }

size_t index_count(int segments) { return static_cast<size_t>(segments) * (segments + 4) * 6; }
}  // namespace

bool draws_terrain(const FrameContext& f, const FrameBody& body) {
    if (!body.body->terrain.present || !f.snap || f.sky_first) return false;
    return glm::length(f.view.camera_position_m - body.state->position_m) < kTerrainRange_radii * body.body->radius_m;
}

TerrainDrawer::TerrainDrawer(const SceneConfig& scene, const ClusterConfig& cluster) : cluster_(cluster) {
    for (const BodyConfig& c : scene.bodies) {
        if (!c.terrain.present) continue;
        auto b = std::make_unique<Body>();
        terrain::BodyRelief relief = terrain::open_body_relief(c);
        if (!relief.fallback.empty()) spdlog::error("{}", relief.fallback);
        b->relief = relief.relief;
        terrain::TileStore::Options o;
        o.workers = c.terrain.workers;
        o.capacity = c.terrain.cache_tiles;
        o.segments = c.terrain.segments;
        o.horizon = true;  // the relief's shadows
        b->store = std::make_unique<terrain::TileStore>(b->relief, o);
        b->settings.budget_px = c.terrain.error_budget_px;
        b->settings.segments = c.terrain.segments;
        b->gpu_capacity = c.terrain.cache_tiles;
        bodies_[c.id] = std::move(b);
    }
    if (bodies_.empty()) return;
    lit_ = std::make_unique<GlProgram>("terrain.vert", "terrain.frag", "#define TERRAIN_AIR 0\n");
    for (const BodyConfig& c : scene.bodies)
        if (c.terrain.present && c.atmosphere.present && !air_)
            air_ = std::make_unique<GlProgram>("terrain.vert", "terrain.frag", "#define TERRAIN_AIR 1\n");
}

TerrainDrawer::~TerrainDrawer() = default;

terrain::TerrainCut TerrainDrawer::cut_for(const FrameContext& f, const FrameBody& body) {
    Body& b = *bodies_.at(body.body->id);
    const glm::dmat3 to_world = body_to_world(*body.state), from_world = glm::transpose(to_world);
    const glm::dvec3 camera_body = from_world * (f.view.camera_position_m - body.state->position_m);
    const terrain::CutView view = terrain::cut_view_for_cluster(cluster_, camera_body, from_world,
                                                                f.snap->camera_orientation, f.snap->head.position_m);
    return terrain::select_cut(*b.relief, view, b.settings, b.ranges);
}

const GlVertexBuffer& TerrainDrawer::gpu_tile(Body& b, const terrain::TileMesh& mesh) {
    const uint64_t id = mesh.key.id();
    const auto found = b.gpu.find(id);
    if (found != b.gpu.end()) {
        b.recent.splice(b.recent.begin(), b.recent, found->second.at);
        return *found->second.buffer;
    }
    while (b.gpu.size() >= b.gpu_capacity && !b.recent.empty()) {  // the least recently drawn goes
        b.gpu.erase(b.recent.back());
        b.recent.pop_back();
    }
    if (!b.indices) {  // every tile of the body has the same triangles: one index buffer for all
        b.indices = std::make_unique<GlIndexBuffer>(mesh.triangle_indices());
    }
    auto buffer = std::make_unique<GlVertexBuffer>(std::vector<int>{3, 3, 3, 4});
    std::vector<float> data;
    for (const auto& v : mesh.gpu_vertices())
        data.insert(data.end(),
                    {v.position.x, v.position.y, v.position.z, v.parent_delta.x, v.parent_delta.y, v.parent_delta.z,
                     v.normal.x, v.normal.y, v.normal.z, v.horizon.x, v.horizon.y, v.horizon.z, v.horizon.w});
    buffer->upload(data);
    buffer->share_indices(*b.indices);
    b.recent.push_front(id);
    GpuTile& t = b.gpu[id];
    t.buffer = std::move(buffer);
    t.at = b.recent.begin();
    return *t.buffer;
}

void TerrainDrawer::set_light(const GlProgram& p, const FrameContext& f, const FrameBody& body,
                              const GpuAtmosphere* air) const {
    const PlanetSun sun = planet_sun(*body.state, f.light, air ? &air->model() : nullptr);
    p.set("u_sun_body", glm::vec3(glm::transpose(body_to_world(*body.state)) * sun.dir_world));
    p.set("u_lit", glm::vec3(static_cast<float>(sun.irradiance / std::numbers::pi)));
    if (!air) return;
    set_atmosphere_params(p, air->model().shader_params());
    bind_atmosphere_tables(p, *air, kTableUnit);
    p.set("u_solar_scale", static_cast<float>(sun.solar_scale));
}

const TerrainDrawer::FrameTiles& TerrainDrawer::frame_tiles(Body& b, const FrameContext& f, const FrameBody& body) {
    if (b.frame.frame != &f || b.frame.snap != f.snap) {
        b.frame.cut = cut_for(f, body);
        b.frame.list = b.store->request(b.frame.cut);
        b.frame.frame = &f;
        b.frame.snap = f.snap;
    }
    return b.frame;
}

void TerrainDrawer::set_view(const GlProgram& p, const ChannelView& view, const FrameBody& body) const {
    p.set("u_projection", glm::mat4(view.frustum->projection(kNear_m, kFar_m)));
    p.set("u_body_to_channel", glm::mat3(view.world_to_channel * body_to_world(*body.state)));
}

void TerrainDrawer::draw(const FrameContext& f, const FrameBody& body, const GlTexture& map, const GpuAtmosphere* air) {
    Body& b = *bodies_.at(body.body->id);
    b.frame.frame = nullptr;  // a new frame: choose the cut again
    const FrameTiles& tiles = frame_tiles(b, f, body);
    const GlProgram& p = air ? *air_ : *lit_;
    p.use();
    set_view(p, f.view, body);
    p.set("u_reflectance", glm::vec3(body.body->tint) * static_cast<float>(body.body->albedo));
    p.set("u_texture", static_cast<int>(kMapUnit));
    p.set("u_pixel_rad", static_cast<float>(pixel_angle_rad(*f.view.frustum)));
    p.set("u_texel_m", static_cast<float>(2.0 * std::numbers::pi * body.body->radius_m / map.width()));
    map.bind(kMapUnit);
    set_light(p, f, body, air);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    TerrainFrameStats& s = b.last;
    s = TerrainFrameStats{};
    s.cut_hash = tiles.cut.hash();
    s.cut_tiles = tiles.cut.tiles.size();
    s.stand_ins = tiles.list.stand_ins;
    const DrawnTiles drawn = draw_tiles(p, b, f.view, body, tiles.cut, tiles.list.meshes);
    s.drawn_tiles = drawn.tiles;
    s.triangles = drawn.triangles;
    s.gpu_meshes = b.gpu.size();
    glDisable(GL_DEPTH_TEST);
    gl::check("terrain (" + body.body->name + ")");
}

void TerrainDrawer::draw_depth(const FrameContext& f, const ChannelView& view, const FrameBody& body) {
    Body& b = *bodies_.at(body.body->id);
    const FrameTiles& tiles = frame_tiles(b, f, body);
    const Meshes seen = meshes_in_view(tiles.list.meshes, view, body);
    if (seen.empty()) return;
    // Compiled on the first use: a scene whose relief never meets a glare probe never needs it.
    if (!depth_) depth_ = std::make_unique<GlProgram>("terrain.vert", "terrain_depth.frag");
    depth_->use();
    set_view(*depth_, view, body);
    draw_tiles(*depth_, b, view, body, tiles.cut, seen);  // not the frame's own draw: not counted
    gl::check("terrain depth (" + body.body->name + ")");
}

TerrainDrawer::Meshes TerrainDrawer::meshes_in_view(const Meshes& meshes, const ChannelView& view,
                                                    const FrameBody& body) {
    const glm::dmat3 from_world = glm::transpose(body_to_world(*body.state));
    const glm::dvec3 camera_body = from_world * (view.camera_position_m - body.state->position_m);
    const glm::dvec3 axis = from_world * (view.channel_to_world * glm::dvec3(0.0, 0.0, -1.0));
    const glm::dvec4 t(view.tangents());
    const double half_rad = std::atan(std::hypot(std::max(t.x, t.y), std::max(t.z, t.w)));  // to a corner
    Meshes out;
    for (const auto& m : meshes) {
        const glm::dvec3 to = m->centre_m - camera_body;
        const double d = glm::length(to);
        if (d > m->bound_radius_m &&
            std::acos(std::clamp(glm::dot(to / d, axis), -1.0, 1.0)) - std::asin(m->bound_radius_m / d) > half_rad)
            continue;
        out.push_back(m);
    }
    return out;
}

// The tiles' meshes, each moved toward its parent's shape by its cut tile's morph distance; returns
// how many meshes and triangles it drew.
TerrainDrawer::DrawnTiles TerrainDrawer::draw_tiles(const GlProgram& p, Body& b, const ChannelView& view,
                                                    const FrameBody& body, const terrain::TerrainCut& cut,
                                                    const Meshes& meshes) {
    DrawnTiles drawn;
    const glm::dmat3 to_world = body_to_world(*body.state);
    const glm::dmat3 body_to_channel = view.world_to_channel * to_world;
    const glm::dvec3 camera_body = glm::transpose(to_world) * (view.camera_position_m - body.state->position_m);
    std::unordered_map<uint64_t, double> morph_far;
    for (const terrain::CutTile& t : cut.tiles) morph_far[t.key.id()] = t.morph_far_m;
    for (const auto& mesh : meshes) {
        const GlVertexBuffer& buffer = gpu_tile(b, *mesh);
        const auto far = morph_far.find(mesh->key.id());  // a stand-in keeps its own shape
        p.set("u_morph_far_m", far == morph_far.end() ? 0.0f : static_cast<float>(far->second));
        p.set("u_centre_channel_m", glm::vec3(body_to_channel * (mesh->centre_m - camera_body)));
        p.set("u_centre_body_m", glm::vec3(mesh->centre_m));
        buffer.bind();
        const size_t count = index_count(mesh->segments);
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT, nullptr);
        drawn.triangles += count / 3;
        ++drawn.tiles;
    }
    return drawn;
}

void TerrainDrawer::wait_idle() {
    for (auto& [id, b] : bodies_) b->store->wait_idle();
}

void TerrainDrawer::set_build_hook(std::function<void(const terrain::TileKey&)> hook) {
    for (auto& [id, b] : bodies_) b->store->set_build_hook(hook);
}

}  // namespace cupola
