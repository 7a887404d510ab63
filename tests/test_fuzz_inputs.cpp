// The fuzzers' regression inputs (tests/fuzz_inputs/TARGET/, docs/fuzzing.md):
// each file, through the same reader as its fuzz target, is read or refused
// with one InputError line naming the file, never another exception. (Under
// AddressSanitizer scripts/fuzz.sh runs them too.)
#include "mesh.h"
#include "scene.h"
#include "stl_io.h"
#include "sweep/sweep_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

namespace fs = std::filesystem;

namespace {

const fs::path kInputs = fs::path(ARMOUR_SOURCE_DIR) / "tests" / "fuzz_inputs";

// Every input of `target` through `read`; returns how many there were.
int check_inputs(const std::string &target, const std::function<void(const std::string &)> &read) {
    int count = 0;
    for (const auto &entry : fs::directory_iterator(kInputs / target)) {
        const std::string path = entry.path().string();
        SCOPED_TRACE(path);
        ++count;
        try {
            read(path);
        } catch (const armour::InputError &e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        } catch (const std::exception &e) {
            ADD_FAILURE() << "not an InputError: " << e.what();
        }
    }
    return count;
}

} // namespace

TEST(FuzzInputs, ScenesAreReadOrRefusedInOneLine) {
    EXPECT_GT(check_inputs("scene", [](const std::string &path) { (void)armour::load_scene(path); }), 0);
}

TEST(FuzzInputs, StlsAreReadOrRefusedInOneLine) {
    EXPECT_GT(check_inputs("stl",
                           [](const std::string &path) {
                               const armour::TriangleMesh mesh = armour::read_stl(path);
                               for (const auto &t : mesh.triangles)
                                   for (const int v : t)
                                       ASSERT_TRUE(v >= 0 &&
                                                   static_cast<std::size_t>(v) < mesh.vertices.size());
                           }),
              0);
}

// The hand-made inputs name ../../../scenes/tilt_cube.toml as their scene, so
// that the reader gets past the scene check to the key it is tested on.
TEST(FuzzInputs, SweepFilesAreReadOrRefusedInOneLine) {
    EXPECT_GT(check_inputs("sweep", [](const std::string &path) { (void)armour::read_sweep_file(path); }), 0);
}
