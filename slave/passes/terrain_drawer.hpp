#pragma once
// The planets and moons with terrain (config/scene_config.hpp, TerrainConfig), drawn as relief
// instead of a smooth sphere: each frame the cut of the body's tile quadtree is chosen once for the
// whole cluster (common/terrain/cluster_cut_view.hpp: every channel of the dome, from the
// snapshot's camera, so every node picks the same tiles), its meshes are taken from the tile store
// (built on worker threads; a tile not built yet is drawn as its ancestor) and drawn camera-relative
// in float with a depth test, each lit by the Sun on its slopes and by the sky (shaders/terrain.frag).
// Writes the colour, the G-buffer (reflectance, distance) and the scene target's depth.
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <unordered_map>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/frame_context.hpp"
#include "terrain/terrain_cut.hpp"
#include "terrain/tile_store.hpp"

namespace cupola {

class GpuAtmosphere;

// Whether a body is drawn as relief this frame: it has terrain and the camera is within
// kTerrainRange_radii of its centre. Farther out the relief is below a pixel (10 km of relief at
// ten radii of the Earth is 1.6e-4 rad, 0.4 px of a 4k dome) and the smooth sphere, with its
// antialiased limb, draws it (BodyPass). From the snapshot alone: the same on every channel.
// Not in a frame whose sky is drawn first (FrameContext::sky_first: the camera inside another
// body's air), which draws the bodies beyond the air into a colour target without a depth buffer:
// the body is drawn as its sphere then. (A planet with terrain never draws its own ground, so its
// own air is never drawn first.)
constexpr double kTerrainRange_radii = 10.0;
bool draws_terrain(const FrameContext& f, const FrameBody& body);

// What the last frame's draw of one body did.
struct TerrainFrameStats {
    uint64_t cut_hash = 0;   // TerrainCut::hash(): the same on every node of the cluster
    size_t cut_tiles = 0;    // tiles in the cut
    size_t drawn_tiles = 0;  // meshes drawn (fewer while ancestors stand in)
    int stand_ins = 0;       // cut tiles drawn as an ancestor
    size_t triangles = 0;    // drawn
    size_t gpu_meshes = 0;   // tile meshes held on the GPU
};

class TerrainDrawer {
public:
    TerrainDrawer(const SceneConfig& scene, const ClusterConfig& cluster);
    ~TerrainDrawer();
    bool has_terrain(uint16_t body_id) const { return bodies_.count(body_id) != 0; }
    // The cut for the whole cluster from this frame's camera (the same for every channel).
    terrain::TerrainCut cut_for(const FrameContext& f, const FrameBody& body);
    // Draws the body's relief into the bound scene target (depth test on, then off again).
    // map: the body's map (BodyPass::texture); air: its atmosphere, or null.
    void draw(const FrameContext& f, const FrameBody& body, const GlTexture& map, const GpuAtmosphere* air);
    // Draws the body's relief into the bound target as depth alone (the logarithmic depth of the
    // true distance), seen through another view of the same frame (the glare probe's, around the
    // Sun), depth test on: the tiles this frame's draw() drew, so that the relief drawn is the
    // relief that hides the Sun's glare.
    void draw_depth(const FrameContext& f, const ChannelView& view, const FrameBody& body);
    const TerrainFrameStats& last_frame(uint16_t body_id) const { return bodies_.at(body_id)->last; }
    terrain::TileStoreStats store_stats(uint16_t body_id) const { return bodies_.at(body_id)->store->stats(); }
    // Blocks until every body's store has built what was asked for (tests, offline rendering).
    void wait_idle();
    // A test hook on every body's store (TileStore::set_build_hook).
    void set_build_hook(std::function<void(const terrain::TileKey&)> hook);

private:
    struct GpuTile {
        std::unique_ptr<GlVertexBuffer> buffer;
        std::list<uint64_t>::iterator at;
    };
    struct FrameTiles {  // what one frame draws of a body
        const FrameContext* frame = nullptr;
        const Snapshot* snap = nullptr;
        terrain::TerrainCut cut;
        terrain::TileDrawList list;
    };
    struct Body {
        std::shared_ptr<const terrain::Relief> relief;
        std::unique_ptr<terrain::TileStore> store;
        terrain::TileRangeCache ranges;
        terrain::CutSettings settings;
        std::unique_ptr<GlIndexBuffer> indices;     // every tile's triangles, shared (outlives the tiles)
        std::unordered_map<uint64_t, GpuTile> gpu;  // by TileKey::id
        std::list<uint64_t> recent;                 // most recently drawn first
        size_t gpu_capacity = 0;
        TerrainFrameStats last;
        FrameTiles frame;  // the last frame's
    };
    const GlVertexBuffer& gpu_tile(Body& b, const terrain::TileMesh& mesh);
    void set_light(const GlProgram& p, const FrameContext& f, const FrameBody& body, const GpuAtmosphere* air) const;
    // The frame's cut and tiles for the body (chosen and requested once a frame).
    const FrameTiles& frame_tiles(Body& b, const FrameContext& f, const FrameBody& body);
    void set_view(const GlProgram& p, const ChannelView& view, const FrameBody& body) const;
    using Meshes = std::vector<std::shared_ptr<const terrain::TileMesh>>;
    struct DrawnTiles {
        size_t tiles = 0, triangles = 0;
    };
    DrawnTiles draw_tiles(const GlProgram& p, Body& b, const ChannelView& view, const FrameBody& body,
                          const terrain::TerrainCut& cut, const Meshes& meshes);
    // The meshes whose bound reaches into a view's cone.
    static Meshes meshes_in_view(const Meshes& meshes, const ChannelView& view, const FrameBody& body);

    const ClusterConfig cluster_;  // a copy: the renderer is often made from a temporary
    std::map<uint16_t, std::unique_ptr<Body>> bodies_;
    std::unique_ptr<GlProgram> lit_, air_;  // without and with an atmosphere
    std::unique_ptr<GlProgram> depth_;      // depth alone (draw_depth; compiled on its first use)
};

}  // namespace cupola
