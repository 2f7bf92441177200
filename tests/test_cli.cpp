// Every program answers --help, and bad command lines or configs get a clear message and a
// non-zero exit, never a crash.
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "util/child_process.hpp"

using namespace cupola;
using namespace std::chrono_literals;

namespace {
struct Result {
    int code;
    std::string output;
};
Result run(const std::string& name, const std::vector<std::string>& args) {
    const std::string dir = test::scratch_dir("cli/" + name);
    std::vector<std::string> argv = {test::bin_path(args.at(0))};
    argv.insert(argv.end(), args.begin() + 1, args.end());
    ChildProcess p(argv, dir + "/out.log");
    auto rc = p.wait_for(60s);
    EXPECT_TRUE(rc.has_value()) << name << " did not finish";
    return {rc.value_or(-1), test::read_text(dir + "/out.log")};
}
}  // namespace

TEST(Cli, EveryProgramAnswersHelp) {
    for (const char* prog : {"cupola-master", "cupola-slave", "cupola-loopback", "cupola-stitch"}) {
        Result r = run(std::string("help_") + prog, {prog, "--help"});
        EXPECT_EQ(r.code, 0) << prog;
        EXPECT_NE(r.output.find("--config"), std::string::npos) << prog << ": " << r.output;
    }
}

TEST(Cli, BadArgumentsAreNamed) {
    Result missing = run("missing_config", {"cupola-master"});
    EXPECT_NE(missing.code, 0);
    EXPECT_NE(missing.output.find("--config"), std::string::npos) << missing.output;

    Result nofile = run("no_such_file", {"cupola-master", "--config", "/nonexistent/cluster.json"});
    EXPECT_NE(nofile.code, 0);
    EXPECT_NE(nofile.output.find("/nonexistent/cluster.json"), std::string::npos) << nofile.output;

    Result frames = run("bad_frames", {"cupola-loopback", "--config", test::source_path("configs/dome-4ch.json"),
                                       "--frames", "zero", "--out", "/tmp/x"});
    EXPECT_NE(frames.code, 0);
    EXPECT_NE(frames.output.find("--frames"), std::string::npos) << frames.output;

    Result channel = run("bad_channel", {"cupola-slave", "--config", test::source_path("configs/dome-4ch.json"),
                                         "--channel", "ceiling", "--out", "/tmp/x"});
    EXPECT_EQ(channel.code, 2);
    EXPECT_NE(channel.output.find("ceiling"), std::string::npos) << channel.output;

    const std::string dir = test::scratch_dir("cli/bad_config_file");
    test::write_text(dir + "/c.json", R"({"cluster_id": 1, "key_file": "nope.key"})");
    Result cfg = run("bad_config", {"cupola-master", "--config", dir + "/c.json"});
    EXPECT_EQ(cfg.code, 2);
    EXPECT_NE(cfg.output.find("key_file"), std::string::npos) << cfg.output;
    EXPECT_NE(cfg.output.find("c.json"), std::string::npos) << cfg.output;
}
