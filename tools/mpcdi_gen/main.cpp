// cupola-mpcdi-gen: writes the MPCDI calibration of an ideal dome (common/calibration/ideal_dome.hpp:
// N equal projectors on the springline, each aimed across the dome) and checks it against the
// analytic model, after reading the file back.
//   cupola-mpcdi-gen --out FILE.mpcdi [--projectors N] [--lens fisheye|normal] [--lens-fov DEG] ...
//                    [--config-template FILE --config-out FILE] [--images DIR] [--check]
//                    [--stitch-frames F0 F1 ... --stitch-out FILE.png]   (warped projector frames back onto the dome)
// Exit status: 0 written (and, with --check, within the bounds), 1 a failure or a bound missed,
// 2 bad arguments.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "calibration/ideal_dome_checks.hpp"
#include "calibration/ideal_dome_package.hpp"
#include "calibration/ideal_dome_warp.hpp"
#include "calibration/mpcdi_package.hpp"
#include "mpcdi_gen_outputs.hpp"
#include "util/cli_parse.hpp"

namespace {

struct Options {
    cupola::ProjectorRing ring;
    cupola::IdealCalibrationSpec spec;
    std::string lens = "fisheye";
    std::string out, config_template, config_out, images_dir, stitch_out;
    std::vector<std::string> stitch_frames;
    int stitch_size = 512;
    bool check = false;
};

void add_options(CLI::App& app, Options& o) {
    app.add_option("--out", o.out, "the .mpcdi package to write")->required();
    app.add_option("--projectors", o.ring.count, "projectors around the springline")->check(CLI::Range(1, 64));
    app.add_option("--lens", o.lens, "fisheye (f-theta, full circle) | normal (pinhole)")
        ->check(CLI::IsMember({"fisheye", "normal"}));
    app.add_option("--lens-fov", o.ring.lens.fov_deg, "lens field of view, degrees (fisheye: the circle)");
    app.add_option("--lens-shift", o.ring.lens.shift_y, "normal lens: vertical shift, fraction of the height");
    app.add_option("--distance", o.ring.distance_fraction, "projector distance from the centre, dome radii");
    app.add_option("--pitch", o.ring.pitch_deg, "projector pitch, degrees");
    app.add_option("--raster-width", o.ring.raster_width, "projector raster")->check(CLI::Range(2, 16384));
    app.add_option("--raster-height", o.ring.raster_height, "projector raster")->check(CLI::Range(2, 16384));
    app.add_option("--radius", o.spec.dome.radius_m, "dome radius, metres");
    app.add_option("--grid-columns", o.spec.grid_columns, "warp grid points across")->check(CLI::Range(2, 16384));
    app.add_option("--grid-rows", o.spec.grid_rows, "warp grid points down")->check(CLI::Range(2, 16384));
    app.add_option("--alpha-width", o.spec.alpha_width, "alpha map texels (0: half the raster)")
        ->check(CLI::Range(0, 16384));
    app.add_option("--alpha-height", o.spec.alpha_height, "alpha map texels (0: half the raster)")
        ->check(CLI::Range(0, 16384));
    app.add_option("--ramp-px", o.spec.ramp.width_px, "blend ramp width, projector pixels");
    app.add_option("--gamma", o.spec.projector_gamma, "projector gamma");
    app.add_option("--margin-deg", o.spec.frustum_margin_deg, "channel frustum margin, degrees");
    app.add_option("--config-template", o.config_template, "cluster config whose non-channel fields are copied")
        ->check(CLI::ExistingFile);
    app.add_option("--config-out", o.config_out, "cluster config to write, one channel per region");
    app.add_option("--images", o.images_dir, "folder for the alpha maps, a test-pattern frame, the stitched dome");
    app.add_option("--stitch-frames", o.stitch_frames, "projector frames (one per projector, in order) to stitch")
        ->check(CLI::ExistingFile);
    app.add_option("--stitch-out", o.stitch_out, "the stitched check image (PNG) of --stitch-frames");
    app.add_option("--stitch-size", o.stitch_size, "its size in pixels")->check(CLI::Range(16, 8192));
    app.add_flag("--check", o.check, "read the file back and check geometry (p99 0.5 px) and blend (2 %)");
}

std::vector<cupola::ProjectorWarp> read_back(const std::string& file, const std::vector<cupola::ProjectorWarp>& made) {
    const auto package = cupola::MpcdiPackage::open(file);
    std::vector<cupola::ProjectorWarp> warps;
    for (const auto& w : made) warps.push_back(package.read_region(w.region_id));
    return warps;
}

bool report_checks(const std::vector<cupola::IdealProjector>& projectors,
                   const std::vector<cupola::ProjectorWarp>& warps) {
    const auto g = cupola::measure_warp_geometry(projectors, warps);
    std::printf(
        "warp geometry: %zu pixels on the dome, %zu not shown, error median %.4f px, p99 %.4f px, max %.3f px\n",
        g.pixels, g.not_shown, g.median_px, g.p99_px, g.max_px);
    const auto b = cupola::measure_blend_flatness(projectors, warps, {});
    std::printf(
        "blend: %zu samples (%zu in overlaps, %zu dark), light %.4f .. %.4f, max deviation %.2f %% "
        "(overlaps %.2f %%)\n",
        b.samples, b.overlap_samples, b.dark_samples, b.min_light, b.max_light, 100.0 * b.max_deviation,
        100.0 * b.max_overlap_deviation);
    cupola::ProjectorFrameOptions naive;
    naive.blend = false;
    const auto n = cupola::measure_blend_flatness(projectors, warps, naive);
    std::printf("naive (no blend): light %.4f .. %.4f, max deviation %.2f %%\n", n.min_light, n.max_light,
                100.0 * n.max_deviation);
    return g.not_shown == 0 && g.p99_px <= 0.5 && g.median_px <= 0.1 && b.dark_samples == 0 && b.max_deviation <= 0.02;
}

int run(Options& o) {
    o.ring.lens.kind = o.lens == "normal" ? cupola::LensKind::Normal : cupola::LensKind::Fisheye;
    o.spec.projectors = cupola::projector_ring(o.ring);
    o.spec.source = o.out;
    const auto warps = cupola::ideal_projector_warps(o.spec);
    cupola::write_ideal_dome_mpcdi(o.out, warps);
    std::cout << "wrote " << o.out << " (" << warps.size() << " regions)\n";
    const auto projectors = cupola::make_projectors(o.spec.dome, o.spec.projectors);
    const auto back = read_back(o.out, warps);
    if (!o.config_out.empty()) {
        if (o.config_template.empty()) throw std::invalid_argument("--config-out needs --config-template");
        cupola::write_calibrated_config(o.config_template, o.config_out, o.out, back);
        std::cout << "wrote " << o.config_out << "\n";
    }
    if (!o.images_dir.empty()) {
        for (const auto& path : cupola::write_calibration_images(o.images_dir, projectors, back))
            std::cout << "wrote " << path << "\n";
    }
    if (!o.stitch_frames.empty()) {
        if (o.stitch_out.empty()) throw std::invalid_argument("--stitch-frames needs --stitch-out");
        std::vector<double> gammas;
        for (const auto& w : back) gammas.push_back(w.projector_gamma);
        cupola::write_stitched_frames(o.stitch_out, projectors, o.stitch_frames, gammas, o.stitch_size);
        std::cout << "wrote " << o.stitch_out << "\n";
    }
    return o.check && !report_checks(projectors, back) ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"cupola-mpcdi-gen: the MPCDI calibration of an ideal dome lit by projectors on its springline"};
    Options o;
    add_options(app, o);
    if (const auto stop = cupola::parse_command_line(app, argc, argv, "cupola-mpcdi-gen")) return *stop;
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::cerr << "cupola-mpcdi-gen: " << e.what() << "\n";
        return 1;
    }
}
