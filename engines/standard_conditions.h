// Defaults every room shares, written once: standard gravity and fresh water.
// Scenes override both (run.gravity, fluid.fluid_density); these are what a
// run uses when they say nothing.
#pragma once

namespace armour {

constexpr double kStandardGravity = 9.81;     // m/s^2, along -z
constexpr double kFreshWaterDensity = 1000.0; // kg/m^3

} // namespace armour
