// The cupola-sky probe as scripts drive it: queries on stdin or as arguments, one JSON object per line.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.hpp"

using namespace cupola;

namespace {
std::pair<int, std::string> run(const std::string& cmd) { return test::run_shell(cmd); }

std::vector<nlohmann::json> json_lines(const std::string& out) {
    std::vector<nlohmann::json> v;
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);) v.push_back(nlohmann::json::parse(line));
    return v;
}

const std::string kSky = test::bin_path("cupola-sky");
}  // namespace

TEST(SkyProbe, AnswersOneJsonObjectPerQueryLine) {
    const auto [status, out] =
        run("printf '# Meeus 47.a, 1992 Apr 12.0 TD\\nposition moon 1992-04-11T23:58:59Z\\n\\n"
            "eclipse 2006-03-29T10:11:18Z\\nnext-solar 2006-03-25T00:00:00Z\\n"
            "next-lunar 2022-11-04T00:00:00Z\\n' | " +
            kSky);
    ASSERT_EQ(status, 0) << out;
    const auto j = json_lines(out);
    ASSERT_EQ(j.size(), 4u) << out;
    // The Moon (UTC + 59.184 s is 1.8 s short of Meeus's instant; the Moon moves 0.5"/s).
    EXPECT_NEAR(j[0]["ra_deg"].get<double>(), 134.688470, 5.0 / 3600);
    EXPECT_NEAR(j[0]["dec_deg"].get<double>(), 13.768368, 5.0 / 3600);
    EXPECT_NEAR(j[0]["distance_km"].get<double>(), 368409.7, 2.0);
    // The 2006 total solar eclipse at greatest eclipse, then found from four days before.
    EXPECT_EQ(j[1]["type"], "total");
    EXPECT_NEAR(j[1]["lat_deg"].get<double>(), 23.15, 0.3);
    EXPECT_NEAR(j[1]["lon_deg"].get<double>(), 16.75, 0.3);
    EXPECT_NEAR(j[1]["magnitude"].get<double>(), 1.052, 0.003);
    EXPECT_EQ(j[2]["type"], "total");
    EXPECT_EQ(j[2]["peak_utc"].get<std::string>().substr(0, 16), "2006-03-29T10:11");
    for (const char* key : {"lat_deg", "lon_deg", "magnitude", "gamma"}) EXPECT_TRUE(j[2][key].is_number()) << key;
    EXPECT_EQ(j[3]["type"], "total");
    EXPECT_EQ(j[3]["peak_utc"].get<std::string>().substr(0, 15), "2022-11-08T10:5");
    EXPECT_TRUE(j[3]["penumbral_magnitude"].is_number());
    // The same query as arguments gives the same answer as on stdin.
    const auto [s2, one] = run(kSky + " next-solar 2006-03-25T00:00:00Z");
    ASSERT_EQ(s2, 0) << one;
    EXPECT_EQ(nlohmann::json::parse(one), j[2]);
}

TEST(SkyProbe, BadLinesAndBadArgumentsAreNamed) {
    const auto [status, out] =
        run("printf 'position vulcan 2024-01-01T00:00:00Z\\neclipse noon\\nwobble\\n"
            "position sun\\nposition sun 2024-04-08T18:17:00Z\\n' | " +
            kSky);
    EXPECT_EQ(status, 2);
    const auto j = json_lines(out);
    ASSERT_EQ(j.size(), 5u) << out;
    EXPECT_EQ(j[0]["line"], 1);
    EXPECT_NE(j[0]["error"].get<std::string>().find("line 1: unknown body 'vulcan'"), std::string::npos) << j[0];
    EXPECT_NE(j[1]["error"].get<std::string>().find("\"noon\" is not an ISO 8601 UTC time"), std::string::npos) << j[1];
    EXPECT_NE(j[2]["error"].get<std::string>().find("unknown query 'wobble'"), std::string::npos) << j[2];
    EXPECT_NE(j[3]["error"].get<std::string>().find("'position' takes BODY TIME"), std::string::npos) << j[3];
    EXPECT_TRUE(j[4].contains("ra_deg"));  // the run goes on after bad lines
    const auto [s1, msg] = run(kSky + " position mars yesterday 2>&1");
    EXPECT_EQ(s1, 2);
    EXPECT_NE(msg.find("cupola-sky: \"yesterday\" is not an ISO 8601 UTC time"), std::string::npos) << msg;
    const auto [s2, msg2] = run(kSky + " --frobnicate 2>&1");
    EXPECT_EQ(s2, 2);
    EXPECT_NE(msg2.find("frobnicate"), std::string::npos) << msg2;
    const auto [s3, help] = run(kSky + " --help");
    EXPECT_EQ(s3, 0);
    EXPECT_NE(help.find("next-lunar"), std::string::npos);
}

TEST(SkyProbe, AnswersForEveryBodyOfTheSolarSystemScene) {
    // Every body of configs/scenes/solar-system.json but the Earth (the probe is geocentric).
    const auto scene = nlohmann::json::parse(test::read_text(test::source_path("configs/scenes/solar-system.json")));
    std::string queries;
    std::vector<std::string> bodies;
    for (const auto& b : scene["bodies"]) {
        if (b["ephemeris"] == "earth") continue;
        bodies.push_back(b["ephemeris"]);
        queries += "position " + bodies.back() + " 2026-12-03T20:00:00Z\\n";
    }
    ASSERT_EQ(bodies.size(), 15u);
    const auto [status, out] = run("printf '" + queries + "' | " + kSky);
    ASSERT_EQ(status, 0) << out;
    const auto j = json_lines(out);
    ASSERT_EQ(j.size(), bodies.size()) << out;
    for (size_t i = 0; i < j.size(); ++i) {
        EXPECT_GT(j[i]["distance_km"].get<double>(), 3.0e5) << bodies[i];
        EXPECT_GE(j[i]["ra_deg"].get<double>(), 0.0) << bodies[i];
        EXPECT_LT(j[i]["ra_deg"].get<double>(), 360.0) << bodies[i];
    }
    // Pluto in late 2026 is in Capricornus/Aquarius, about 38 AU away.
    EXPECT_NEAR(j[9]["distance_km"].get<double>() / 1.495978707e8, 35.9, 1.5) << j[9];
    // Jupiter's moons (the last four) stand within 0.2 degrees of it (Callisto reaches 0.17 at
    // opposition) and within 0.02 AU of its distance.
    const auto& jupiter = j[5];
    for (size_t i = 10; i < 14; ++i) {
        const double d_ra = std::remainder(j[i]["ra_deg"].get<double>() - jupiter["ra_deg"].get<double>(), 360.0);
        const double d_dec = j[i]["dec_deg"].get<double>() - jupiter["dec_deg"].get<double>();
        const double cos_dec = std::cos(jupiter["dec_deg"].get<double>() * 3.14159265358979 / 180.0);
        EXPECT_LT(std::hypot(d_ra * cos_dec, d_dec), 0.2) << bodies[i];
        EXPECT_NEAR(j[i]["distance_km"].get<double>(), jupiter["distance_km"].get<double>(), 0.02 * 1.495978707e8)
            << bodies[i];
    }
}
