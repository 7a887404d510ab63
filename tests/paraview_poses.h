// ParaView's own reader on a result (`armour run`'s OUT/bodies.xdmf): every
// recorded step is there, and every unit is where bodies.h5 says it is.
//
// Description
//     pvpython (Debian's python3-paraview, run offscreen) opens the XDMF with
//     the Xdmf3 reader and lists each step's points with their body
//     (tests/paraview_poses.py). Each body's points, taken back to the unit
//     frame with the step's recorded pose (/bodies/position, orientation),
//     must be the same at every step, and at the first step they must be the
//     vertices of one of the units' shapes (OUT/units/*/shape.stl): so the
//     grid ParaView draws is each unit posed as recorded. Points are float32
//     in the file, hence the tolerance of 1e-5 (1 + |x|) m.
//     CI installs pvpython (scripts/debian-packages.txt); a test without it
//     says so with GTEST_SKIP.
//
// Usage
//     if (!have_pvpython()) GTEST_SKIP() << "pvpython not found (Debian: python3-paraview)";
//     expect_paraview_shows_the_poses(out_dir);
#pragma once

#include "bodies_file.h"
#include "stl_io.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

inline bool have_pvpython() {
    return std::system("command -v pvpython > /dev/null 2>&1") == 0;
}

inline void expect_paraview_shows_the_poses(const std::filesystem::path &out) {
    namespace fs = std::filesystem;
    const fs::path table = out.parent_path() / (out.filename().string() + ".paraview.txt"),
                   log = out.parent_path() / (out.filename().string() + ".paraview.log");
    const std::string command =
        "timeout 300 pvpython --force-offscreen-rendering " ARMOUR_SOURCE_DIR "/tests/paraview_poses.py " +
        (out / "bodies.xdmf").string() + " " + table.string() + " > " + log.string() + " 2>&1";
    std::stringstream log_text;
    const int status = std::system(command.c_str());
    log_text << std::ifstream(log).rdbuf();
    ASSERT_EQ(status, 0) << log_text.str();

    const armour::BodiesFile rec = armour::read_bodies_file((out / "bodies.h5").string());
    std::vector<std::vector<Eigen::Vector3d>> shapes; // every unit's vertices
    for (const auto &unit : fs::directory_iterator(out / "units"))
        shapes.push_back(armour::read_stl((unit.path() / "shape.stl").string()).vertices);
    const auto tolerance = [](const Eigen::Vector3d &x) { return 1e-5 * (1.0 + x.norm()); };

    std::vector<std::vector<Eigen::Vector3d>> first; // per body: its points in the unit frame, step 0
    std::ifstream in(table);
    std::size_t step = 0;
    for (std::string line; std::getline(in, line); ++step) {
        SCOPED_TRACE("step " + std::to_string(step));
        ASSERT_LT(step, rec.steps());
        std::istringstream row(line);
        double t = 0.0;
        std::size_t points = 0, cells = 0;
        row >> t >> points >> cells;
        EXPECT_NEAR(t, rec.time[step], 1e-9 * (1.0 + rec.time[step]));
        std::vector<std::vector<Eigen::Vector3d>> framed(rec.bodies());
        for (std::size_t i = 0; i < points; ++i) {
            Eigen::Vector3d p;
            int body = -1;
            row >> p.x() >> p.y() >> p.z() >> body;
            ASSERT_TRUE(row && body >= 0 && static_cast<std::size_t>(body) < rec.bodies()) << "point " << i;
            const auto b = static_cast<std::size_t>(body);
            framed[b].push_back(rec.orientation[step][b].conjugate() * (p - rec.position[step][b]));
        }
        if (step == 0) {
            first = framed;
            continue;
        }
        for (std::size_t b = 0; b < rec.bodies(); ++b) {
            ASSERT_EQ(framed[b].size(), first[b].size()) << "body " << b;
            for (std::size_t i = 0; i < framed[b].size(); ++i)
                ASSERT_LT((framed[b][i] - first[b][i]).norm(), tolerance(rec.position[step][b]))
                    << "body " << b << " point " << i << " is not where the recorded pose puts it";
        }
    }
    EXPECT_EQ(step, rec.steps()) << "ParaView sees " << step << " steps of " << rec.steps();
    ASSERT_FALSE(first.empty());
    for (std::size_t b = 0; b < rec.bodies(); ++b) {
        bool matched = false;
        for (const auto &shape : shapes) {
            bool all = shape.size() == first[b].size();
            for (std::size_t i = 0; all && i < shape.size(); ++i) {
                bool found = false;
                for (const Eigen::Vector3d &v : shape)
                    found = found || (first[b][i] - v).norm() < tolerance(rec.position[0][b]);
                all = found;
            }
            matched = matched || all;
        }
        EXPECT_TRUE(matched) << "body " << b << " is not one of the units' shapes, posed";
    }
}
