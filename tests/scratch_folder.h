// A fresh, empty folder for the test that is running, named after it and this
// process (TMP/armour_<what>_<test>_<pid>), so that tests run side by side
// (ctest -j) never share one; whatever an earlier killed run left there goes.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace armour_test {

inline std::filesystem::path fresh_test_folder(const std::string &what) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        ("armour_" + what + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
         std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

} // namespace armour_test
