// How `armour run` runs an OpenFOAM tool (fluid_case/foam_tool.h) and says
// why one failed, in one line naming the tool and its log: its FOAM FATAL
// line (even when it exited 0, as mpirun may), a program that cannot start,
// or its exit status when its log is empty; what a tool leaves running ends
// with it. Stand-in tools are shell lines.
#include "foam_tool.h"
#include "input_error.h"
#include "scratch_folder.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

class FoamTool : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = armour_test::fresh_test_folder("tool"); }
    void TearDown() override { fs::remove_all(dir_); }
    // The message run_tool throws for `script` run by sh as tool "tool"
    // (empty: it did not throw).
    std::string error_of(const std::string &script) const {
        try {
            armour::run_tool("tool", {"sh", "-c", script}, dir_, 1.0, false);
        } catch (const armour::InputError &e) {
            return e.what();
        }
        return "";
    }
    fs::path dir_;
};

TEST_F(FoamTool, AToolThatEndsWellThrowsNothingAndKeepsItsLog) {
    EXPECT_EQ(error_of("echo 'Time = 0.5'; exit 0"), "");
    EXPECT_TRUE(fs::is_regular_file(dir_ / "log.tool"));
}

TEST_F(FoamTool, AFatalLineFailsTheToolEvenWhenItExitsZero) {
    const std::string error = error_of("echo '--> FOAM FATAL ERROR: no such patch'; exit 0");
    EXPECT_NE(
        error.find("tool failed (see " + (dir_ / "log.tool").string() + "): FOAM FATAL ERROR: no such patch"),
        std::string::npos)
        << error;
}

TEST_F(FoamTool, AnEmptyLogGivesTheExitStatus) {
    const std::string error = error_of("exit 3");
    EXPECT_NE(error.find("tool failed (see " + (dir_ / "log.tool").string() +
                         "): exit status 3, nothing in its log"),
              std::string::npos)
        << error;
}

TEST_F(FoamTool, ALogGivesItsLastThreeLines) {
    const std::string error = error_of("echo one; echo two; echo three; echo four; exit 1");
    EXPECT_NE(error.find("): two | three | four"), std::string::npos) << error;
}

TEST_F(FoamTool, AProgramThatCannotStartIsNamed) {
    std::string error;
    try {
        armour::run_tool("tool", {"armour-no-such-program"}, dir_, 1.0, false);
    } catch (const armour::InputError &e) {
        error = e.what();
    }
    EXPECT_NE(error.find("could not run armour-no-such-program"), std::string::npos) << error;
}

// A tool that ends before what it started (an mpirun gone before its ranks)
// leaves it to armour, which ends it before run_tool returns: the stand-in's
// `sleep` (its pid in a file) no longer exists then, not even as a zombie.
TEST_F(FoamTool, WhatAToolLeftBehindEndsBeforeRunToolReturns) {
    EXPECT_EQ(error_of("sleep 30 & echo $! > left.pid; exit 0"), "");
    std::ifstream in(dir_ / "left.pid");
    pid_t left = 0;
    ASSERT_TRUE(in >> left);
    ASSERT_GT(left, 0);
    EXPECT_EQ(::kill(left, 0), -1) << "process " << left << " still exists";
    EXPECT_EQ(errno, ESRCH);
}

} // namespace
