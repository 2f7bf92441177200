#pragma once
// Renders one channel's frustum slice of the dome for a snapshot, into offscreen RGBA32F
// targets; the output stage (slave/output/) takes the final colour texture from there, and the
// frame is read back as a linear float image only when asked. Needs a current GL 4.5 context.
// The pipeline is one ordered list of render passes (slave/passes/render_pass.hpp), built in
// the constructor (slave/scene_renderer.cpp) and run in order every frame.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "image/frame_image.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// What the atmosphere passes did: only bodies with an atmosphere get tables, and a pass runs
// only while the body's top-of-atmosphere sphere can touch the channel's frustum.
struct AtmosphereStats {
    int tables_built_or_loaded = 0;  // at construction, one per body with an atmosphere
    long passes_run = 0;             // summed over frames
    long passes_skipped = 0;         // atmosphere entirely outside the frustum
    long passes_marched = 0;         // of the passes run, those that marched every pixel
    long sky_view_renders = 0;       // sky-view tables rendered (only when their inputs change)
    long halos_added = 0;            // draws that added the glare's halo (then no draw of its own)
    long surfaces_drawn = 0;         // draws that drew their planet's surface (then no body pass)
};

// The wall time of one frame, per pass, when pass timing is on (SceneRenderer::set_pass_timing).
struct FrameTimings {
    // Per pass name, in the order the passes ran: prepare() and every step, up to a glFinish().
    std::vector<std::pair<std::string, double>> passes_ms;
    double read_back_ms = 0.0;  // render()'s read-back; 0 when the frame was only drawn
    double frame_ms = 0.0;      // the whole draw() (its CPU set-up included), plus read_back_ms
};

class RenderPass;
class OverlayPass;
class GlTexture;

class TerrainDrawer;

class SceneRenderer {
public:
    SceneRenderer(const ClusterConfig& cluster, const ChannelConfig& channel, const SceneConfig& scene);
    ~SceneRenderer();
    // draw() and read_back(): the frame as a linear float image, row 0 at the top.
    Image render(const Snapshot& snapshot);
    // Renders the frame into the final colour target and waits for the GPU; reads nothing back.
    void draw(const Snapshot& snapshot);
    // The final colour of the last draw() (RGBA32F, linear, GL row 0 at the bottom).
    const GlTexture& color() const;
    // Reads the last draw()'s colour back (glReadPixels), row 0 at the top; counted.
    Image read_back();
    // The last draw()'s G-buffer (rgb reflectance, a distance in metres; -1 where nothing was
    // drawn), row 0 at the top: for tests of the geometry (the terrain's cracks).
    Image read_geometry() const;
    // The drawer of the bodies with terrain (its cut and tile store), for tests and the benchmark.
    TerrainDrawer& terrain();
    // How many times a frame was read back since construction.
    uint64_t read_backs() const;
    // Frames whose G-buffer was cleared: those in which some pass reads it.
    uint64_t geometry_clears() const;
    // Frames whose colour was cleared: all but those whose sky is drawn first (set_sky_first).
    uint64_t color_clears() const;
    AtmosphereStats atmosphere_stats() const;
    // The newest finished glare occlusion-query results (for the frame report): after render()
    // they are normally this frame's (render() ends with a glFinish), else an earlier frame's.
    const std::vector<GlareMeasurement>& glare_measurements() const;

    // Pass timing, off by default (then draw() waits for the GPU only once, at its end): when
    // on, draw() also waits after every pass and records the wall times of the frame.
    void set_pass_timing(bool on);
    // Planets and moons drawn as points (wholly or fading into their disc) since construction.
    long planet_points_drawn() const;
    // Whether the nearest atmosphere's draw may add the glare's halo when it covers the channel
    // (on by default); off, the glare pass always upsamples the halo on its own (the two must
    // give the same image: tests/test_atmosphere_fused_draws.cpp).
    void set_halo_with_atmosphere(bool on);
    // Whether the atmosphere's draw may draw its planet's surface itself, from inside the air (on
    // by default; AtmospherePass::draws_surface); off, the body pass draws it into the G-buffer
    // (the same image again: tests/test_atmosphere_fused_draws.cpp).
    void set_surface_with_atmosphere(bool on);
    // Whether each star is judged against the sky behind it (on by default; StarPass,
    // shared/star_visibility.glsl); off, the magnitude limits and the exposure alone decide (for
    // comparison: by day the stars then show over the sky).
    void set_stars_see_the_sky(bool on);
    // Whether a frame's sky may be drawn first, before the stars, the Sun and the bodies, which
    // then take the air in front of them themselves (on by default; AtmospherePass::sky_first,
    // slave/passes/beyond_the_air.hpp): no colour clear and no blend for the sky. Off (or with
    // the stars not judged against the sky), they are drawn before it and the atmosphere's draw
    // multiplies them by its transmittance (the same image: tests/test_sky_first.cpp).
    void set_sky_first(bool on);
    // How often the star pass rendered its per-star sky weights (passes/star_sky_weights.hpp).
    long star_weight_renders() const;
    // The overlay pass (null when the scene has no overlays).
    const OverlayPass* overlays() const;
    // The last frame's timings while pass timing is on (empty before the first timed frame).
    const FrameTimings& last_frame_timings() const;

    // The passes' names in the order they run.
    std::vector<std::string> pass_names() const;
    // Puts a pass into the list before the one at `position` (pass_names().size(): last).
    // Throws std::out_of_range for a position past the end and std::logic_error (naming the
    // passes) when the list's passes cannot share the frame's targets in the new order.
    void insert_pass(size_t position, std::unique_ptr<RenderPass> pass);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace cupola
