// JONSWAP spectrum and the component list of an irregular wave train.
//
// Description
//     S(f) = alpha g^2 (2 pi)^-4 f^-5 exp(-5/4 (fp/f)^4) gamma^r,
//     r = exp(-(f - fp)^2 / (2 sigma^2 fp^2)), sigma = 0.07 (f <= fp), 0.09 above
//     (Hasselmann et al. 1973); gamma = 1 is Pierson-Moskowitz. alpha is not
//     an input: the discrete spectrum is scaled so that 4 sqrt(m0) = Hs (Hm0)
//     exactly over the components generated.
//
//     Components: `count` (even) frequencies f_j = j df, df = 2 fp / count,
//     from 0.5 fp up to ~2.5 fp (the band carrying > 97 % of the energy for
//     gamma = 3.3), fp itself one of them. Deterministic amplitudes
//     a_j = sqrt(2 S(f_j) df) and random phases (seeded): the train repeats
//     every 1 / df = count Tp / 2 seconds, and one repeat period holds
//     exactly the target spectrum (no sampling error in Hm0 or Tp from the
//     signal itself; random-amplitude generation would add ~1/sqrt(count)).
//
// Usage
//     const IrregularWaves w = jonswap_components(0.06, 1.6, 3.3, 40, 7);
//     const IrregularWaves v = jonswap_components(scene.waves->jonswap_sea());
//     // w.frequency[j] (Hz), w.amplitude[j] (m), w.phase[j] (rad)
#pragma once

#include <cstdint>
#include <vector>

namespace armour {

constexpr int kMaxWaveComponents = 200; // each costs one cos() per inlet face per step

struct IrregularWaves {
    std::vector<double> frequency; // Hz
    std::vector<double> amplitude; // m, a_j (height 2 a_j)
    std::vector<double> phase;     // rad, eta = sum a_j cos(k_j x - 2 pi f_j t + phase_j)
    double frequency_step = 0.0;   // Hz; the train repeats every 1 / frequency_step s
    double shape_scale = 0.0;      // m^2/Hz: the target density is shape_scale * jonswap_shape(f, fp, gamma)
};

// A JONSWAP sea state as a scene gives it ([waves] irregular, a [[series]]
// step): Hm0 (m), Tp (s), peak enhancement, component count (even), phase seed.
struct JonswapSea {
    double hs = 0.0;
    double tp = 0.0;
    double gamma = 3.3;
    int components = 40;
    std::uint64_t seed = 1;
};

// Unnormalised JONSWAP shape (alpha = 1, g = 1): only ratios matter here.
double jonswap_shape(double f, double peak_frequency, double gamma);

// count even, >= 4, <= kMaxWaveComponents (checked by the scene).
IrregularWaves jonswap_components(double hs, double tp, double gamma, int count, std::uint64_t seed);
// The one train of a sea state: the case writer's inlet components, the
// damage analysis' target Tm0,2 and a series step's length all come from it.
IrregularWaves jonswap_components(const JonswapSea &sea);

// s: the train's mean period Tm0,2 = sqrt(m0 / m2) over its components
// (Van der Meer's Tm of s_om and N for a target train).
double target_tm02(const IrregularWaves &waves);

} // namespace armour
