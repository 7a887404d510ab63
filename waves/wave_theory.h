// Linear wave kinematics, the choice of a regular-wave theory, its validity
// and the breaking limits at a wave maker.
//
// Description
//     Plain C++ (no OpenFOAM): the scene checks and the flume's case writer
//     use it before anything runs. SI units; g is |gravity| (m/s^2).
//
//     Ursell number Ur = H L^2 / h^3 (L the linear wavelength). The theories
//     of OpenFOAM's libwaveModels and where this project lets each run:
//       StokesII  Ur <= 8 pi^2 / 3 (~26.3): above it the second harmonic makes
//                 a secondary crest in the trough (the textbook limit);
//       StokesV   Ur <= 8 pi^2 / 3 as well, for steeper waves (H / L0 > 0.02,
//                 where second order misses more than a few percent);
//       cnoidal   Ur > 8 pi^2 / 3 and kh < pi / 4 (h / L < 1/8: shallow water);
//       streamFunction (Fenton): any non-breaking wave, but v1912's model
//                 reads Fenton's solution (waveLength, uMean, Bjs, Ejs) and
//                 solves nothing; no solver here: refused.
//     `auto` picks StokesII, StokesV or cnoidal by these limits. Breaking at
//     the wave maker: H / h <= 0.78 (McCowan) and H <= 0.142 L tanh(kh)
//     (Miche, 1/7 in deep water).
//
// Usage
//     const double L = wavelength(1.6, 0.4, 9.81);          // m
//     const std::string theory = regular_theory("auto", 0.08, 1.6, 0.4, 9.81);
//     const std::string why = regular_wave_refusal(theory, 0.08, 1.6, 0.4, 9.81); // "" = fine
#pragma once

#include <string>

namespace armour {

constexpr double kStokesIIUrsellLimit = 26.318945069609; // 8 pi^2 / 3
constexpr double kDepthBreakingRatio = 0.78;             // H / h, McCowan
constexpr double kMicheSteepness = 0.142;                // H / L in deep water, Miche
constexpr double kStokesVSteepness = 0.02;               // H / L0 above which auto picks StokesV
// Rayleigh-distributed heights: the largest of ~1000 waves of an irregular
// train is ~1.8 Hs (the train the breaking and mesh checks must hold).
constexpr double kLargestWaveOverHs = 1.8;
// OpenFOAM v1912's StokesI/II and irregularMultiDirectional find L by 100
// fixed-point steps L = L0 tanh(2 pi h / L), which converge ever more slowly
// as kh falls: their L is off by 4e-4 at kh = 0.34, 3e-3 at 0.29, 3 % at
// 0.23, 56 % at 0.11 (docs/waves.md). Below this kh they are refused.
constexpr double kStockWavelengthMinKh = 0.34;

// k (1/m) of a wave of `period` (s) in `depth` (m): omega^2 = g k tanh(k h), Newton to 1e-14.
double wave_number(double period, double depth, double g);
double wavelength(double period, double depth, double g);
// m/s: linear theory's group velocity, c/2 (1 + 2kh / sinh 2kh).
double group_velocity(double period, double depth, double g);
// H L^2 / h^3.
double ursell_number(double height, double period, double depth, double g);
// Miche: the steepest wave of this period in this depth, m.
double miche_height(double period, double depth, double g);

// `theory`: StokesII | StokesV | cnoidal | streamFunction | auto; returns the
// stock model's name (auto resolved).
std::string regular_theory(const std::string &theory, double height, double period, double depth, double g);
// Why the wave cannot be made with this (resolved) theory: breaking, or the
// theory's validity (which limit, with the numbers); "" when it can.
std::string regular_wave_refusal(const std::string &theory, double height, double period, double depth,
                                 double g);

} // namespace armour
