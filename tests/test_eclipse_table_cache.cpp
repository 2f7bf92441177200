// The eclipse table kept on disk between runs (eclipse/eclipse_reference.hpp,
// load_or_compute_eclipse_lut): the first run computes and stores it, the next reads the file
// (shown by a file whose texels were changed on purpose coming back as stored), a damaged file is
// replaced by the computed table, and another limb darkening is another file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "eclipse/eclipse_reference.hpp"
#include "image/table_file.hpp"
#include "support/test_support.hpp"

using namespace cupola;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 9, kH = 9;  // small, so the computed table is quick

// Points CUPOLA_CACHE_DIR at a fresh folder for the test and back afterwards.
class EclipseTableCache : public ::testing::Test {
protected:
    void SetUp() override {
        if (const char* d = std::getenv("CUPOLA_CACHE_DIR")) saved_ = d;
        dir_ = test::scratch_dir("eclipse_table_cache");
        setenv("CUPOLA_CACHE_DIR", dir_.c_str(), 1);
    }
    void TearDown() override { setenv("CUPOLA_CACHE_DIR", saved_.c_str(), 1); }
    std::vector<fs::path> tables() const {
        std::vector<fs::path> out;
        for (const auto& e : fs::directory_iterator(dir_))
            if (e.path().extension() == ".exr") out.push_back(e.path());
        return out;
    }
    std::string dir_, saved_;
};

void expect_same(const shading::Texture2DData& a, const shading::Texture2DData& b) {
    ASSERT_EQ(a.texels.size(), b.texels.size());
    for (size_t i = 0; i < a.texels.size(); ++i) EXPECT_EQ(a.texels[i], b.texels[i]) << "texel " << i;
}

}  // namespace

TEST_F(EclipseTableCache, TheFirstRunStoresTheTableAndTheNextReadsIt) {
    const auto computed = eclipse::compute_eclipse_lut(0.6, kW, kH);
    expect_same(eclipse::load_or_compute_eclipse_lut(0.6, kW, kH), computed);
    const auto files = tables();
    ASSERT_EQ(files.size(), 1u);
    EXPECT_EQ(files[0].filename().string().rfind("eclipse-table-", 0), 0u) << files[0];

    // A table with other texels under the same name comes back as stored: it was read, not computed.
    auto marked = computed;
    marked.texels[kW + 1] = glm::vec4(0.25f, 0.25f, 0.25f, 1.0f);
    ASSERT_TRUE(write_table_file(files[0], marked, "cupola-eclipse-table-v1"));
    expect_same(eclipse::load_or_compute_eclipse_lut(0.6, kW, kH), marked);
}

TEST_F(EclipseTableCache, ADamagedFileIsReplacedByTheComputedTable) {
    eclipse::load_or_compute_eclipse_lut(0.6, kW, kH);
    const auto files = tables();
    ASSERT_EQ(files.size(), 1u);
    test::write_text(files[0].string(), "not an EXR file");
    expect_same(eclipse::load_or_compute_eclipse_lut(0.6, kW, kH), eclipse::compute_eclipse_lut(0.6, kW, kH));
    // Rewritten: it now reads back as the table.
    shading::Texture2DData back;
    std::string why;
    EXPECT_TRUE(read_table_file(files[0], kW, kH, "cupola-eclipse-table-v1", back, why)) << why;
}

TEST_F(EclipseTableCache, AnotherLimbDarkeningOrSizeIsAnotherFile) {
    const auto a = eclipse::load_or_compute_eclipse_lut(0.6, kW, kH);
    const auto b = eclipse::load_or_compute_eclipse_lut(0.0, kW, kH);
    eclipse::load_or_compute_eclipse_lut(0.6, kW, 17);
    EXPECT_EQ(tables().size(), 3u);
    // Partial phases differ with the limb darkening (a uniform disc loses light faster at first contact).
    bool differ = false;
    for (size_t i = 0; i < a.texels.size(); ++i) differ = differ || a.texels[i] != b.texels[i];
    EXPECT_TRUE(differ);
}

TEST(TableFile, AFileOfAnotherFormatOrSizeIsRefusedWithTheReason) {
    const std::string dir = test::scratch_dir("table_file_refused");
    shading::Texture2DData t;
    t.width = 3;
    t.height = 2;
    t.texels.assign(6, glm::vec4(0.5f));
    const fs::path f = fs::path(dir) / "t.exr";
    ASSERT_TRUE(write_table_file(f, t, "format-a"));
    shading::Texture2DData back;
    std::string why;
    EXPECT_FALSE(read_table_file(f, 3, 2, "format-b", back, why));
    EXPECT_NE(why.find("format \"format-a\", expected \"format-b\""), std::string::npos) << why;
    EXPECT_FALSE(read_table_file(f, 4, 2, "format-a", back, why));
    EXPECT_NE(why.find("size 3x2x4, expected 4x2x4"), std::string::npos) << why;
    t.texels[2].y = -1.0f;
    ASSERT_TRUE(write_table_file(f, t, "format-a"));
    EXPECT_FALSE(read_table_file(f, 3, 2, "format-a", back, why));
    EXPECT_NE(why.find("negative"), std::string::npos) << why;
    EXPECT_FALSE(read_table_file(fs::path(dir) / "missing.exr", 3, 2, "format-a", back, why));
}
