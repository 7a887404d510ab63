// waves/: linear dispersion, theory choice and limits, JONSWAP components,
// Mansard-Funke separation on synthetic records with known incident and
// reflected parts, zero-crossing statistics. docs/waves.md.
#include "jonswap.h"
#include "wave_separation.h"
#include "wave_theory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using namespace armour;
constexpr double kG = 9.81;

TEST(WaveTheory, WaveNumberSolvesTheDispersionRelation) {
    for (const double h : {0.05, 0.4, 3.0, 50.0})
        for (const double period : {0.8, 1.6, 6.0}) {
            const double k = wave_number(period, h, kG);
            const double omega = 2 * M_PI / period;
            EXPECT_NEAR(kG * k * std::tanh(k * h) / (omega * omega), 1.0, 1e-12) << h << " " << period;
        }
    // Limits: deep L0 = g T^2 / 2 pi, shallow L = T sqrt(g h).
    EXPECT_NEAR(wavelength(1.0, 100.0, kG), kG / (2 * M_PI), 1e-9);
    EXPECT_NEAR(wavelength(60.0, 0.1, kG) / (60.0 * std::sqrt(kG * 0.1)), 1.0, 1e-4);
}

TEST(WaveTheory, AutoPicksByUrsellNumberAndSteepness) {
    // h = 0.4 m, T = 1.6 s: L = 2.84 m, kh = 0.89.
    EXPECT_EQ(regular_theory("auto", 0.02, 1.6, 0.4, kG), "StokesII");     // Ur = 2.9, H/L0 = 0.005
    EXPECT_EQ(regular_theory("auto", 0.09, 1.6, 0.4, kG), "StokesV");      // H/L0 = 0.0225
    EXPECT_EQ(regular_theory("auto", 0.05, 4.0, 0.2, kG), "cnoidal");      // Ur = 120, kh = 0.23
    EXPECT_EQ(regular_theory("StokesII", 0.05, 4.0, 0.2, kG), "StokesII"); // explicit choice kept
}

TEST(WaveTheory, RefusesBreakingAndOutOfRangeWaves) {
    EXPECT_EQ(regular_wave_refusal("StokesII", 0.02, 1.6, 0.4, kG), "");
    EXPECT_NE(regular_wave_refusal("StokesV", 0.33, 3.0, 0.4, kG).find("H / h = 0.825 > 0.78"),
              std::string::npos);
    // Deep water T = 0.8 s: L = 1.0 m, Miche H_max = 0.142 m.
    EXPECT_NE(regular_wave_refusal("StokesV", 0.15, 0.8, 2.0, kG).find("Miche"), std::string::npos);
    EXPECT_NE(regular_wave_refusal("StokesII", 0.05, 4.0, 0.2, kG).find("Ursell"), std::string::npos);
    EXPECT_NE(regular_wave_refusal("cnoidal", 0.02, 1.6, 0.4, kG).find("shallow"), std::string::npos);
    // kh = 0.32 (T = 4 s in 0.4 m, Ursell 4.7): below the stock wavelength iteration's range.
    EXPECT_NE(regular_wave_refusal("StokesII", 0.005, 4.0, 0.4, kG).find("fixed-point"), std::string::npos)
        << regular_wave_refusal("StokesII", 0.005, 4.0, 0.4, kG);
    EXPECT_NE(regular_wave_refusal("streamFunction", 0.02, 1.6, 0.4, kG).find("Fenton"), std::string::npos);
}

TEST(Jonswap, ComponentsCarryHsAndPeakAtTp) {
    const IrregularWaves w = jonswap_components(0.06, 1.6, 3.3, 40, 7);
    ASSERT_EQ(w.frequency.size(), 40u);
    double m0 = 0, top = 0;
    std::size_t peak = 0;
    for (std::size_t j = 0; j < w.amplitude.size(); ++j) {
        m0 += 0.5 * w.amplitude[j] * w.amplitude[j];
        if (w.amplitude[j] > top) {
            top = w.amplitude[j];
            peak = j;
        }
        EXPECT_GE(w.phase[j], 0.0);
        EXPECT_LT(w.phase[j], 2 * M_PI);
    }
    EXPECT_NEAR(4 * std::sqrt(m0), 0.06, 1e-12);
    EXPECT_NEAR(w.frequency[peak], 1 / 1.6, 1e-12);
    EXPECT_NEAR(w.frequency_step, 1 / 32.0, 1e-12); // repeats every count Tp / 2 = 32 s
    EXPECT_NEAR(w.frequency.front(), 0.5 / 1.6, 1e-12);
    EXPECT_NEAR(w.frequency.back(), 49 / 32.0, 1e-12); // 2.45 fp
    // Peak enhancement: S(fp) is gamma times the Pierson-Moskowitz shape.
    EXPECT_NEAR(jonswap_shape(0.625, 0.625, 3.3) / jonswap_shape(0.625, 0.625, 1.0), 3.3, 1e-12);
    // The same seed gives the same phases, another seed others.
    EXPECT_EQ(jonswap_components(0.06, 1.6, 3.3, 40, 7).phase, w.phase);
    EXPECT_NE(jonswap_components(0.06, 1.6, 3.3, 40, 8).phase, w.phase);
}

// eta at x, t of waves a_j cos(k_j x - w_j t + p_j) travelling +x (incident)
// plus reflected ones travelling -x.
struct Train {
    std::vector<double> f, a, phase;
};

double elevation(const Train &in, const Train &out, double x, double t, double h) {
    double eta = 0;
    for (std::size_t j = 0; j < in.f.size(); ++j) {
        const double k = wave_number(1 / in.f[j], h, kG), w = 2 * M_PI * in.f[j];
        eta += in.a[j] * std::cos(k * x - w * t + in.phase[j]);
        eta += out.a[j] * std::cos(-k * x - w * t + out.phase[j]);
    }
    return eta;
}

GaugeArray record(const Train &in, const Train &out, const std::vector<double> &x, double dt, std::size_t n,
                  double h, double noise) {
    GaugeArray g{x, dt, {}};
    std::mt19937_64 rng(3);
    std::normal_distribution<double> gauss(0.0, noise);
    for (const double xp : x) {
        std::vector<double> eta(n);
        for (std::size_t i = 0; i < n; ++i)
            eta[i] = elevation(in, out, xp, static_cast<double>(i) * dt, h) + (noise > 0 ? gauss(rng) : 0.0);
        g.eta.push_back(eta);
    }
    return g;
}

TEST(MansardFunke, SeparatesARegularWaveAndItsReflection) {
    // h = 0.4 m, T = 1.6 s (L = 2.84 m): H_I = 0.08 m, H_R = 0.024 m (Kr = 0.3)
    // at an arbitrary phase; gauges 0.3 m (~L/10) and 0.75 m (~L/4) apart;
    // 1 mm of gauge noise; 10 periods.
    const double h = 0.4, period = 1.6;
    const Train in{{1 / period}, {0.04}, {0.4}}, out{{1 / period}, {0.012}, {2.5}};
    const GaugeArray g = record(in, out, {2.0, 2.3, 2.75}, 0.02, 800, h, 0.001);
    const RegularSeparation r = separate_regular(g, period, h, kG);
    EXPECT_NEAR(r.incident_height / 0.08, 1.0, 0.02);
    EXPECT_NEAR(r.reflected_height / 0.024, 1.0, 0.02);
    EXPECT_NEAR(r.reflection / 0.3, 1.0, 0.02);
    // The gauges alone see between H_I - H_R and H_I + H_R: no single gauge tells H_I.
    const ZeroCrossing z = zero_down_crossing(g.eta[0], g.dt, 0.01);
    EXPECT_GT(std::abs(z.mean_height - 0.08), 0.005);
    // Gauges half a wavelength apart cannot separate.
    const double half = wavelength(period, h, kG) / 2;
    EXPECT_THROW(separate_regular(record(in, out, {0.0, half, 2 * half}, 0.02, 800, h, 0), period, h, kG),
                 std::invalid_argument);
}

TEST(MansardFunke, SeparatesAnIrregularTrainAndItsReflection) {
    // JONSWAP Hs = 0.06 m, Tp = 1.6 s, 40 components (one repeat period,
    // 32 s, is the record); reflected: Kr = 0.25 at independent phases.
    const double h = 0.4;
    const IrregularWaves w = jonswap_components(0.06, 1.6, 3.3, 40, 11);
    const IrregularWaves back = jonswap_components(0.06, 1.6, 3.3, 40, 12);
    Train in{w.frequency, w.amplitude, w.phase}, out{w.frequency, w.amplitude, back.phase};
    for (double &a : out.a)
        a *= 0.25;
    const double fmin = w.frequency.front(), fmax = w.frequency.back();
    const GaugeArray g = record(in, out, {2.0, 2.3, 2.75}, 0.04, 800, h, 0.0);
    const SeparatedWaves s = separate_waves(g, h, kG, fmin, fmax);
    const SpectralParameters inc = spectral_parameters(s.frequency, s.incident, fmin, fmax);
    const SpectralParameters ref = spectral_parameters(s.frequency, s.reflected, fmin, fmax);
    const SpectralParameters all = spectral_parameters(s.frequency, s.measured, fmin, fmax);
    EXPECT_NEAR(inc.hm0 / 0.06, 1.0, 0.02);
    EXPECT_NEAR(std::sqrt(ref.m0 / inc.m0) / 0.25, 1.0, 0.02);
    EXPECT_NEAR(inc.tp, 1.6, 1e-9);
    // The gauges' own Hm0 holds both trains: sqrt(1 + Kr^2) = 1.031 times H_I.
    EXPECT_NEAR(all.hm0 / (0.06 * std::sqrt(1 + 0.25 * 0.25)), 1.0, 0.02);
    // Tm-1,0 of the target spectrum itself.
    double m0 = 0, m1 = 0;
    for (std::size_t j = 0; j < w.frequency.size(); ++j) {
        m0 += w.amplitude[j] * w.amplitude[j];
        m1 += w.amplitude[j] * w.amplitude[j] / w.frequency[j];
    }
    EXPECT_NEAR(inc.tm10 / (m1 / m0), 1.0, 0.02);
}

TEST(ZeroCrossing, MeasuresASineExactly) {
    std::vector<double> eta;
    for (int i = 0; i < 1000; ++i)
        eta.push_back(0.05 * std::sin(2 * M_PI * i * 0.01 / 1.25 + 0.3));
    const ZeroCrossing z = zero_down_crossing(eta, 0.01, 0.01);
    EXPECT_EQ(z.waves, 7); // 8 periods in 10 s, the first and last cut
    EXPECT_NEAR(z.mean_period, 1.25, 1e-6);
    EXPECT_NEAR(z.mean_height, 0.1, 0.1 * 2e-3); // sampled crests: within 0.2 %
}

// 100 waves of 1 to 100 mm, one 1 s sine period each in a scrambled order,
// on a 10 mm set-up, then a 0.5 mm ripple whose down-crossing closes the
// last wave: every statistic is known (a sine sampled 100 times a period
// sums to its exact variance and to zero).
TEST(WaveStatistics, RanksTheWavesOfAKnownRecordAboutItsMeanLevel) {
    std::vector<double> heights;
    for (int k = 1; k <= 100; ++k)
        heights.push_back(1e-3 * ((k * 37) % 101)); // a permutation of 1..100 mm
    heights.push_back(0.5e-3);
    std::vector<double> eta = {0.012}; // above the level: the record opens with a down-crossing
    double m0 = 0.0;
    for (const double h : heights) {
        for (int i = 0; i < 100; ++i)
            eta.push_back(0.01 - 0.5 * h * std::sin(2 * M_PI * i / 100.0));
        m0 += 100 * h * h / 8.0; // each sample's square, summed
    }
    m0 /= static_cast<double>(eta.size());
    const WaveStatistics w = wave_statistics(eta, 0.01, 0.9e-3);
    EXPECT_EQ(w.waves, 100);
    EXPECT_NEAR(w.mean_level, 0.01, 1e-6);
    EXPECT_NEAR(w.hm0, 4.0 * std::sqrt(m0), 1e-6);
    EXPECT_NEAR(w.h_max, 0.100, 1e-12);
    EXPECT_NEAR(w.h_2_percent, 0.098, 1e-12);                 // two of the 100 exceed it
    EXPECT_NEAR(w.h_one_third, 0.5 * (0.100 + 0.068), 1e-12); // the mean of 100 .. 68 mm
    // Waves under min_height do not count: 51 mm and up leaves the 50 highest.
    const WaveStatistics high = wave_statistics(eta, 0.01, 0.0505);
    EXPECT_EQ(high.waves, 50);
    EXPECT_NEAR(high.h_2_percent, 0.099, 1e-12);                 // one of the 50 exceeds it
    EXPECT_NEAR(high.h_one_third, 0.5 * (0.100 + 0.085), 1e-12); // the mean of 100 .. 85 mm
    // 49 waves: none of them is exceeded by as few as 2 %.
    eta.resize(1 + 49 * 100);
    eta.push_back(-1e-3); // closes the 49th
    const WaveStatistics few = wave_statistics(eta, 0.01, 0.9e-3);
    EXPECT_EQ(few.waves, 49);
    EXPECT_TRUE(std::isnan(few.h_2_percent));
    EXPECT_FALSE(std::isnan(few.h_one_third));
    // Still water: no wave, no height.
    const WaveStatistics still = wave_statistics(std::vector<double>(500, 0.0), 0.01, 1e-3);
    EXPECT_EQ(still.waves, 0);
    EXPECT_EQ(still.hm0, 0.0);
    EXPECT_TRUE(std::isnan(still.h_max));
}

TEST(Resample, InterpolatesLinearly) {
    const std::vector<double> y = resample({0.0, 1.0, 3.0}, {0.0, 2.0, 0.0}, 0.5, 1.0, 3);
    EXPECT_DOUBLE_EQ(y[0], 1.0);
    EXPECT_DOUBLE_EQ(y[1], 1.5);
    EXPECT_DOUBLE_EQ(y[2], 0.5);
}

} // namespace
