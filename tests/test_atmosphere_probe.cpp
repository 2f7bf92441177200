// The cupola-atmosphere probe as scripts drive it: queries on stdin, one JSON object per line.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cstdio>
#include <sstream>
#include <string>

#include "support/test_support.hpp"

using namespace cupola;

namespace {
std::pair<int, std::string> run(const std::string& cmd) { return test::run_shell(cmd); }

std::string probe(const std::string& body = "earth") {
    // A cache of each test case's own (the cases run as parallel processes).
    return "CUPOLA_CACHE_DIR=" +
           test::scratch_dir(std::string("atmosphere_probe_cache_") +
                             ::testing::UnitTest::GetInstance()->current_test_info()->name()) +
           " " + test::bin_path("cupola-atmosphere") + " --scene " +
           test::source_path("configs/scenes/earth-physical.json") + " --body " + body + " --paths 64";
}
}  // namespace

TEST(AtmosphereProbe, AnswersOneJsonObjectPerQueryLine) {
    const auto [status, out] = run("printf '0 60 30 0\\n# comment\\n\\n10000 95 88 180\\n' | " + probe());
    ASSERT_EQ(status, 0) << out;
    std::istringstream lines(out);
    std::string line;
    int n = 0;
    while (std::getline(lines, line)) {
        const auto j = nlohmann::json::parse(line);
        for (const char* model : {"reference", "production"}) {
            ASSERT_EQ(j[model]["rgb"].size(), 3u) << line;
            EXPECT_GT(j[model]["luminance"].get<double>(), 0.0) << line;
        }
        EXPECT_NE(j["units"].get<std::string>().find("cd/m^2"), std::string::npos);
        // Production and reference agree to within 20 % on these daylight/sunset queries.
        const double r = j["reference"]["luminance"], p = j["production"]["luminance"];
        EXPECT_NEAR(p, r, 0.2 * r) << line;
        ++n;
    }
    EXPECT_EQ(n, 2);
    // The four numbers as arguments give the same answer as on stdin.
    const auto [s2, one] = run(probe() + " 0 60 30 0");
    ASSERT_EQ(s2, 0);
    EXPECT_EQ(nlohmann::json::parse(one)["production"],
              nlohmann::json::parse(out.substr(0, out.find('\n')))["production"]);
}

TEST(AtmosphereProbe, BadLinesAndBadArgumentsAreNamed) {
    const auto [status, out] = run("printf '0 60 30\\n0 200 30 0\\n0 60 30 0\\n' | " + probe());
    EXPECT_EQ(status, 2);
    std::istringstream lines(out);
    std::string l1, l2, l3;
    std::getline(lines, l1);
    std::getline(lines, l2);
    std::getline(lines, l3);
    EXPECT_EQ(nlohmann::json::parse(l1)["line"], 1);
    EXPECT_NE(l1.find("expected 4 numbers"), std::string::npos) << l1;
    EXPECT_NE(l2.find("[0, 180]"), std::string::npos) << l2;
    EXPECT_TRUE(nlohmann::json::parse(l3).contains("production"));  // the run goes on
    const auto [s1, pluto] = run(probe("pluto") + " 0 0 0 0 2>&1");
    EXPECT_EQ(s1, 2);
    EXPECT_NE(pluto.find("no body named 'pluto'"), std::string::npos) << pluto;
    const auto [s2, fastest] = run(probe() + " --model fastest 0 0 0 0 2>&1");
    EXPECT_EQ(s2, 2);
    EXPECT_NE(fastest.find("unknown atmosphere model 'fastest'"), std::string::npos) << fastest;
    const auto [s3, msg] = run(probe("moon") + " 0 0 0 0 2>&1");
    EXPECT_EQ(s3, 2);
    EXPECT_NE(msg.find("has no atmosphere"), std::string::npos) << msg;
    EXPECT_EQ(run(probe() + " --orders zero 0 0 0 0 2>&1").first, 2);
}
