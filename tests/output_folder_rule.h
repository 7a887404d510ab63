// The output-folder rule (docs/outputs.md), checked the same way for every
// command: --out is refused, exit 2, with the user's file untouched, at a
// working folder (`--out .`), at a folder holding a user's file, and at an
// earlier result the user added a file to; an empty folder is used (`--out .`
// keeps the shell's folder), and a second run replaces the first.
#pragma once

#include "cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace output_rule {

namespace fs = std::filesystem;

struct Outcome {
    int code = -1;
    std::string err;
};

// `armour args...` in-process, with its exit code and stderr.
inline Outcome armour(std::vector<std::string> args) {
    args.insert(args.begin(), "armour");
    std::vector<const char *> argv;
    for (const auto &a : args)
        argv.push_back(a.c_str());
    Outcome o;
    ::testing::internal::CaptureStderr();
    o.code = armour::armour_main(static_cast<int>(argv.size()), argv.data());
    o.err = ::testing::internal::GetCapturedStderr();
    return o;
}

inline std::string read(const fs::path &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline std::set<std::string> names(const fs::path &dir) {
    std::set<std::string> n;
    for (const auto &e : fs::directory_iterator(dir))
        n.insert(e.path().filename().string());
    return n;
}

inline ino_t inode(const fs::path &dir) {
    struct stat s {};
    ::stat(dir.c_str(), &s);
    return s.st_ino;
}

// Runs `run` with the working folder `dir`.
inline Outcome inside(const fs::path &dir, const std::function<Outcome()> &run) {
    const fs::path before = fs::current_path();
    fs::current_path(dir);
    const Outcome o = run();
    fs::current_path(before);
    return o;
}

// Refused with one error line naming `entry`, and `dir` exactly as it was.
inline void expect_refused(const Outcome &o, const fs::path &dir, const std::set<std::string> &before,
                           const std::string &entry, const std::string &text) {
    EXPECT_EQ(o.code, 2) << o.err;
    const std::size_t at = o.err.find("armour: error: --out ");
    ASSERT_NE(at, std::string::npos) << o.err;
    EXPECT_EQ(o.err.find('\n', at), o.err.size() - 1) << o.err;
    EXPECT_NE(o.err.find("'" + entry + "'"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("choose a new or empty folder"), std::string::npos) << o.err;
    EXPECT_EQ(names(dir), before);
    EXPECT_EQ(read(dir / entry), text);
}

// Runs `command` (the command's name, e.g. "armour run") into `out` as
// variant 0 or 1, two settings whose summaries `variant_of` tells apart.
using Command = std::function<Outcome(const std::string &out, int variant)>;
using Variant = std::function<int(const nlohmann::json &summary)>;

inline void check(const fs::path &scratch, const std::string &command, const Command &run,
                  const Variant &variant_of) {
    const std::string text = "a user's notes, not to be lost\n";

    // `--out .` in a working folder.
    const fs::path work = scratch / "work";
    fs::create_directories(work);
    std::ofstream(work / "notes.txt") << text;
    expect_refused(inside(work, [&] { return run(".", 0); }), work, {"notes.txt"}, "notes.txt", text);

    // `--out` at a folder holding a user's file, named from elsewhere.
    const fs::path user = scratch / "user";
    fs::create_directories(user);
    std::ofstream(user / "input.stl") << text;
    expect_refused(run(user.string(), 0), user, {"input.stl"}, "input.stl", text);

    // An empty folder is used, from inside (`--out .`); the folder itself stays.
    const fs::path empty = scratch / "empty";
    fs::create_directories(empty);
    const ino_t folder = inode(empty);
    Outcome o = inside(empty, [&] { return run(".", 0); });
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_EQ(variant_of(nlohmann::json::parse(read(empty / "summary.json"))), 0);

    // A second run replaces the first, entry by entry, in the same folder.
    o = inside(empty, [&] { return run(".", 1); });
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_EQ(inode(empty), folder);
    EXPECT_EQ(variant_of(nlohmann::json::parse(read(empty / "summary.json"))), 1);
    // The marker names the command and lists every entry; nothing else is left.
    std::istringstream marker(read(empty / ".armour-output"));
    std::string line;
    std::getline(marker, line);
    EXPECT_EQ(line, command);
    std::set<std::string> listed = {".armour-output"};
    while (std::getline(marker, line))
        listed.insert(line);
    for (const std::string &name : names(empty))
        EXPECT_TRUE(listed.count(name)) << name << " is not listed in the marker";

    // A user's file added to the earlier result: refused, nothing touched.
    std::ofstream(empty / "later.txt") << text;
    const std::set<std::string> before = names(empty);
    const std::string summary = read(empty / "summary.json");
    expect_refused(run(empty.string(), 0), empty, before, "later.txt", text);
    EXPECT_EQ(read(empty / "summary.json"), summary);
}

} // namespace output_rule
