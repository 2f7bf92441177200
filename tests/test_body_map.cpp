// A body's map prepared on the CPU (slave/passes/body_map.hpp): the prefetch a slave starts
// before its GL context gives the same map as preparing it in place, a map not prefetched is
// prepared when taken, and a missing file is reported where the map is taken.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "config/scene_config.hpp"
#include "gl/gl_texture.hpp"
#include "passes/body_map.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

void expect_same(const BodyMap& a, const BodyMap& b) {
    EXPECT_EQ(a.image.width, b.image.width);
    EXPECT_EQ(a.image.rgb, b.image.rgb);
    ASSERT_EQ(a.mips.size(), b.mips.size());
    for (size_t i = 0; i < a.mips.size(); ++i) EXPECT_EQ(a.mips[i].texels, b.mips[i].texels) << "level " << i + 1;
    EXPECT_EQ(a.mean_rgb, b.mean_rgb);
    EXPECT_EQ(a.grid.cells, b.grid.cells);
}

BodyConfig body(uint16_t id, const std::string& texture, glm::vec3 tint) {
    BodyConfig b;
    b.id = id;
    b.name = "body" + std::to_string(id);
    b.kind = BodyKind::Planet;
    b.texture = texture;
    b.tint = tint;
    return b;
}

}  // namespace

TEST(BodyMap, APrefetchedMapIsTheMapPreparedInPlace) {
    SceneConfig scene;
    scene.bodies = {body(1, "generated:moon", glm::vec3(1.0f)), body(2, "generated:io", glm::vec3(1.0f, 0.9f, 0.6f))};
    std::thread worker = prefetch_body_maps(scene);
    const BodyMap moon = take_body_map("generated:moon", glm::dvec3(1.0));
    const BodyMap io = take_body_map("generated:io", glm::dvec3(glm::vec3(1.0f, 0.9f, 0.6f)));
    worker.join();
    expect_same(moon, prepare_body_map("generated:moon", glm::dvec3(1.0)));
    expect_same(io, prepare_body_map("generated:io", glm::dvec3(glm::vec3(1.0f, 0.9f, 0.6f))));
    // The tint is in the mean and the grid, not in the image.
    EXPECT_EQ(io.image.rgb, prepare_body_map("generated:io", glm::dvec3(1.0)).image.rgb);
    EXPECT_NEAR(io.mean_rgb.b / io.mean_rgb.r, 0.6, 1e-6);
    EXPECT_FALSE(moon.mips.empty());
    EXPECT_EQ(moon.mips.back().width, 1);
}

TEST(BodyMap, AMapNotPrefetchedOrTakenTwiceIsPreparedWhenTaken) {
    SceneConfig scene;
    scene.bodies = {body(1, "generated:moon", glm::vec3(1.0f))};
    std::thread worker = prefetch_body_maps(scene);
    const BodyMap first = take_body_map("generated:moon", glm::dvec3(1.0));
    const BodyMap second = take_body_map("generated:moon", glm::dvec3(1.0));  // prepared again
    worker.join();
    expect_same(first, second);
    // Another tint is another map.
    const BodyMap red = take_body_map("generated:moon", glm::dvec3(1.0, 0.0, 0.0));
    EXPECT_EQ(red.mean_rgb.g, 0.0);
    EXPECT_GT(red.mean_rgb.r, 0.0);
}

TEST(BodyMap, AMissingFileIsReportedWhereTheMapIsTaken) {
    const std::string missing = test::scratch_dir("body_map_missing") + "/no-such-map.jpg";
    SceneConfig scene;
    scene.bodies = {body(1, missing, glm::vec3(1.0f))};
    std::thread worker = prefetch_body_maps(scene);  // the error waits in the prefetch
    try {
        take_body_map(missing, glm::dvec3(1.0));
        FAIL() << "a missing map was taken";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("no-such-map.jpg"), std::string::npos) << e.what();
    }
    worker.join();
}

TEST(BodyMap, TheTextureRefusesAMipChainOfTheWrongLength) {
    test::headless_gl();
    const int w = 8, h = 4;
    const std::vector<float> rgb(static_cast<size_t>(w) * h * 3, 0.5f);
    auto chain = box_filter_mip_chain(w, h, rgb);
    EXPECT_NO_THROW(GlTexture(w, h, rgb, chain));
    chain.pop_back();
    try {
        GlTexture t(w, h, rgb, chain);
        FAIL() << "a short chain was uploaded";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("2 mipmap levels given, 3 needed"), std::string::npos) << e.what();
    }
}
