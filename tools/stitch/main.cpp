// cupola-stitch: stitches the channel frames of a run directory into domemasters.
//   cupola-stitch --config FILE --in DIR --out DIR [--frame N] [--size S]
// Exit status: 0 all frames stitched cleanly, 1 a runtime error or any problem reported
// (missing channel frames, disagreeing snapshot hashes...), 2 bad arguments or config.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

#include "util/cli_parse.hpp"
#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "dome/domemaster_stitcher.hpp"

int main(int argc, char** argv) {
    CLI::App app{"cupola-stitch: stitch channel frames (DIR/<channel>/frame_NNNNNN.{exr,png}) into domemasters"};
    std::string config_file, in_dir, out_dir;
    std::optional<uint64_t> frame;
    int size = 0;
    app.add_option("--config", config_file, "cluster config (JSON)")->required()->check(CLI::ExistingFile);
    app.add_option("--in", in_dir, "run directory holding one folder per channel")
        ->required()
        ->check(CLI::ExistingDirectory);
    app.add_option("--out", out_dir, "where the domemasters are written")->required();
    app.add_option("--frame", frame, "stitch only this frame index");
    app.add_option("--size", size, "domemaster size in pixels (default: the config's output.domemaster_size)")
        ->check(CLI::Range(1, 32768));
    if (const auto stop = cupola::parse_command_line(app, argc, argv, "cupola-stitch")) return *stop;

    cupola::ClusterConfig config;
    try {
        config = cupola::load_cluster_config(config_file);
    } catch (const cupola::ConfigError& e) {
        std::cerr << "cupola-stitch: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "cupola-stitch: " << config_file << ": " << e.what() << "\n";
        return 2;
    }

    try {
        const cupola::StitchReport report = cupola::stitch_run_directory(config, in_dir, out_dir, frame, size);
        for (const auto& path : report.written) std::cout << "wrote " << path << "\n";
        for (const auto& p : report.problems) std::cerr << "cupola-stitch: problem: " << p << "\n";
        std::cout << "stitched " << report.frames.size() << " frame(s), " << report.problems.size() << " problem(s)\n";
        return report.problems.empty() ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "cupola-stitch: " << e.what() << "\n";
        return 1;
    }
}
