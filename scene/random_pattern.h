// A [[pattern]] with placement = "random": the grid's slots, each unit turned
// uniformly at random and moved a little within its slot, then set at the
// lowest height where it clears the slope and the units placed before it
// (docs/scenes.md, docs/stability.md). With placement = "seated" the slots
// are taken from the toe up, row by row, and each unit is then slid down the
// face into the first trough, as a placer lets a unit down onto the rows
// below. Internal to the scene library (scene_setup.cpp).
#pragma once

#include "collider.h"
#include "scene.h"

#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

namespace armour {

// The grid of one pattern on its slope wall, as scene_setup.cpp lays it out.
struct PatternGrid {
    const SceneWall *slope = nullptr;
    Eigen::Vector3d origin, along, normal;  // the toe at y = 0 (m); up the face; out of it
    Eigen::Quaterniond turn;                // the unit frame onto the slope's (x up, y across, z out)
    double first = 0.0;                     // m up the face: the first row's slot
    double spacing = 0.0;                   // m between slots
    double size = 0.0;                      // m: the unit's collided size along and across, facing the slope
    Eigen::Vector3d domain_min, domain_max; // m: run.domain_min/max, which every unit stays inside
};

// The units already in the scene when a pattern is placed (its [[body]]
// entries: a settle in stages, fluid.settle_stages): whether a pose clears
// them all by the pattern's gap, and their highest point above the face (m).
struct UnitsBefore {
    std::function<bool(const BodyInit &)> clear;
    double top = 0.0;
};

// The poses of pattern `p` (its unit `unit`, collided as `collider`, no part
// farther than `reach` (m) from its centre) with placement "random" or "seated", clear
// of `walls`, of `before` and of each other, its rows from p.first_row up. Throws InputError, its message
// `key` (the scene file and the pattern's key up to its last part: "FILE: key 'pattern.0.") + "placement':
// ...", when a slot holds no pose after many draws.
std::vector<BodyInit> random_pattern(const ScenePattern &p, const PatternGrid &grid, int unit,
                                     const UnitTemplate &unit_template, const Collider &collider,
                                     double reach, double Dn, const std::vector<Wall> &walls,
                                     const UnitsBefore &before, const std::string &key);

} // namespace armour
