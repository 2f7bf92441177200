// Where the programs find data/ (common/util/data_files.hpp): $CUPOLA_DATA_DIR alone when set,
// else next to the installed programs, else the source tree. The installed layout itself is run
// by the ctest packaging_installed (tests/test_packaging.sh).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "support/test_support.hpp"
#include "util/data_files.hpp"

namespace fs = std::filesystem;
using cupola::data_file;

namespace {

// Sets or unsets CUPOLA_DATA_DIR for one test and restores what was there.
class DataDirVariable {
public:
    explicit DataDirVariable(const char* value) {
        if (const char* old = std::getenv("CUPOLA_DATA_DIR")) {
            saved_ = old;
            had_ = true;
        }
        if (value)
            setenv("CUPOLA_DATA_DIR", value, 1);
        else
            unsetenv("CUPOLA_DATA_DIR");
    }
    ~DataDirVariable() {
        if (had_)
            setenv("CUPOLA_DATA_DIR", saved_.c_str(), 1);
        else
            unsetenv("CUPOLA_DATA_DIR");
    }

private:
    std::string saved_;
    bool had_ = false;
};

}  // namespace

TEST(DataFiles, BuildTreeProgramsReadTheSourceTree) {
    DataDirVariable unset(nullptr);
    // The test programs live in build/bin, with no installed share/cupola next to them.
    ASSERT_FALSE(fs::exists(fs::path(cupola::test::bin_path("")) / "../share/cupola/data"));
    EXPECT_EQ(data_file("time/delta_t.csv"), fs::path(cupola::test::source_path("data/time/delta_t.csv")).string());
    EXPECT_EQ(data_file("stars/bright_stars.csv"),
              fs::path(cupola::test::source_path("data/stars/bright_stars.csv")).string());
}

TEST(DataFiles, TheVariableWinsOverTheSourceTree) {
    const std::string dir = cupola::test::scratch_dir("data_files_variable");
    fs::create_directories(fs::path(dir) / "time");
    cupola::test::write_text(dir + "/time/delta_t.csv", "year,delta_t_s\n1700,1\n1800,2\n");
    DataDirVariable set(dir.c_str());
    EXPECT_EQ(data_file("time/delta_t.csv"), (fs::path(dir) / "time/delta_t.csv").lexically_normal().string());
}

TEST(DataFiles, AFileMissingUnderTheVariableIsAnErrorNamingIt) {
    const std::string dir = cupola::test::scratch_dir("data_files_missing");
    DataDirVariable set(dir.c_str());
    // The source tree has the file, but the variable says where to look: no silent fallback.
    try {
        data_file("time/delta_t.csv");
        FAIL() << "data_file found time/delta_t.csv outside $CUPOLA_DATA_DIR";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("time/delta_t.csv"), std::string::npos) << what;
        EXPECT_NE(what.find(dir), std::string::npos) << what;
        EXPECT_NE(what.find("CUPOLA_DATA_DIR"), std::string::npos) << what;
        EXPECT_EQ(what.find(cupola::test::source_path("data")), std::string::npos) << what;
    }
}

TEST(DataFiles, AFileNowhereIsAnErrorNamingEveryPlace) {
    DataDirVariable unset(nullptr);
    try {
        data_file("time/no_such_table.csv");
        FAIL() << "data_file returned a path for a file that does not exist";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("share/cupola/data/time/no_such_table.csv"), std::string::npos) << what;
        EXPECT_NE(what.find(cupola::test::source_path("data/time/no_such_table.csv")), std::string::npos) << what;
    }
}
