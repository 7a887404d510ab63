// Incident and reflected waves from an array of gauges (Mansard & Funke
// 1980), spectral wave parameters and zero-crossing statistics.
//
// Description
//     Along a flume (x the direction the incident waves travel) each
//     frequency's complex amplitude at gauge p is modelled as
//
//         B_p = Z_I exp(-i k x_p) + Z_R exp(+i k x_p)       (eta = Re B e^{i w t})
//
//     with k from linear dispersion; Z_I and Z_R are the least-squares
//     solution over the gauges (Mansard & Funke's method with three or more
//     gauges; the normal equations are solved directly). A frequency is
//     unresolved where the gauges see the two waves alike (all spacings near
//     a multiple of L/2: 1 - |sum_p exp(2ikx_p)|^2 / P^2 < 0.05); its
//     densities are interpolated from the neighbouring resolved frequencies.
//     Mansard & Funke's spacing for a peak wavelength L: x12 ~ L/10,
//     L/6 < x13 < L/3, x13 not L/5 or 3L/10.
//
//     Spectra are variance densities (m^2/Hz) on the record's DFT frequencies
//     j / (n dt). Hm0 = 4 sqrt(m0), Tp = 1 / the peak frequency, Tm-1,0 =
//     m-1 / m0, all over [f_min, f_max]; the reflection coefficient is
//     sqrt(m0_R / m0_I).
//
// Usage
//     GaugeArray a{{2.0, 2.3, 2.9}, 0.01, {eta1, eta2, eta3}};
//     const SeparatedWaves s = separate_waves(a, 0.4, 9.81, 0.3, 1.6);
//     const SpectralParameters in = spectral_parameters(s.frequency, s.incident, 0.3, 1.6);
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace armour {

struct GaugeArray {
    std::vector<double> x;                // m, gauge positions along the flume
    double dt = 0.0;                      // s, uniform sampling
    std::vector<std::vector<double>> eta; // m, elevation above still water, one record per gauge
};

struct SeparatedWaves {
    std::vector<double> frequency; // Hz
    std::vector<double> incident;  // m^2/Hz
    std::vector<double> reflected; // m^2/Hz
    std::vector<double> measured;  // m^2/Hz, the gauges' mean (incident and reflected together)
    std::vector<bool> resolved;    // false: interpolated (gauge spacing degenerate there)
};

struct SpectralParameters {
    double m0 = 0.0;   // m^2
    double hm0 = 0.0;  // m
    double tp = 0.0;   // s
    double tm10 = 0.0; // s, Tm-1,0
    double tm02 = 0.0; // s, sqrt(m0 / m2), ~ the mean zero-crossing period
};

struct RegularSeparation {
    double incident_height = 0.0;  // m, 2 |Z_I| at the wave's frequency (first harmonic)
    double reflected_height = 0.0; // m
    double reflection = 0.0;       // |Z_R| / |Z_I|
};

struct ZeroCrossing {
    double mean_height = 0.0; // m, crest to trough between zero down-crossings
    double mean_period = 0.0; // s
    int waves = 0;
    std::vector<double> heights; // m, each wave's, in time order
};

// The total waves at one gauge (incident and reflected together), about
// their mean level (a set-up on a berm left out).
struct WaveStatistics {
    double hm0 = 0.0;         // m, 4 sqrt(m0)
    double h_max = NAN;       // m, by zero down-crossing; NaN without a wave
    double h_one_third = NAN; // m, the highest third's mean; NaN under 3 waves
    double h_2_percent = NAN; // m, the height 2 % of the waves exceed; NaN under 50 waves (none
                              // of a shorter record's heights is exceeded by as few as 2 %)
    double mean_level = 0.0;  // m, the record's mean (its set-up)
    int waves = 0;
};

// Spectra from f_min to f_max (Hz; at least three gauges, equal records).
SeparatedWaves separate_waves(const GaugeArray &gauges, double depth, double g, double f_min, double f_max);
SpectralParameters spectral_parameters(const std::vector<double> &frequency,
                                       const std::vector<double> &density, double f_min, double f_max);
// One frequency, 1 / period, fitted over the whole records (best over a whole number of periods).
RegularSeparation separate_regular(const GaugeArray &gauges, double period, double depth, double g);
// Waves higher than min_height only (ripples between waves do not count).
ZeroCrossing zero_down_crossing(const std::vector<double> &eta, double dt, double min_height);
// eta (m) sampled every dt (s); its mean is taken off before anything else,
// and only waves higher than min_height count (as zero_down_crossing).
WaveStatistics wave_statistics(std::vector<double> eta, double dt, double min_height);
// y(t) linearly interpolated at t0 + i dt, i < n (t increasing).
std::vector<double> resample(const std::vector<double> &t, const std::vector<double> &y, double t0, double dt,
                             std::size_t n);

} // namespace armour
