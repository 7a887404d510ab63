// A sweep case's lock (apps/sweep/case_runner.h) is free again after an
// attempt that throws before its run starts (an unreadable plan, a record it
// cannot write), so the next sweep in the same process, or a case_is_locked()
// check, does not take a case that nothing runs for a running one.
#include "case_runner.h"
#include "input_error.h"
#include "scratch_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

class CaseRunnerLock : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = armour_test::fresh_test_folder("case"); }
    void TearDown() override { fs::remove_all(dir_); }
    void write(const std::string &name, const std::string &text) const { std::ofstream(dir_ / name) << text; }
    fs::path dir_;
};

TEST_F(CaseRunnerLock, AnUnreadablePlanThrowsAndFreesTheLock) {
    write("plan.json", "{ not json");
    EXPECT_THROW(armour::run_case(dir_, "/bin/false"), armour::InputError);
    EXPECT_FALSE(armour::case_is_locked(dir_));
}

TEST_F(CaseRunnerLock, ARecordItCannotWriteThrowsAndFreesTheLock) {
    write("plan.json", R"({"scene_hash": "abc", "duration": 1.0})");
    // case.json a folder with a file in it: the attempt's record cannot replace it.
    fs::create_directories(dir_ / "case.json");
    write("case.json/keep", "x");
    EXPECT_ANY_THROW(armour::run_case(dir_, "/bin/false"));
    EXPECT_FALSE(armour::case_is_locked(dir_));
    EXPECT_TRUE(fs::is_regular_file(dir_ / "case.json" / "keep"));
}

} // namespace
