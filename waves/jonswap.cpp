#include "jonswap.h"

#include <cmath>
#include <random>

namespace armour {

double jonswap_shape(double f, double peak_frequency, double gamma) {
    const double fp = peak_frequency;
    const double sigma = f <= fp ? 0.07 : 0.09;
    const double r = std::exp(-(f - fp) * (f - fp) / (2.0 * sigma * sigma * fp * fp));
    return std::pow(f, -5.0) * std::exp(-1.25 * std::pow(fp / f, 4.0)) * std::pow(gamma, r);
}

IrregularWaves jonswap_components(double hs, double tp, double gamma, int count, std::uint64_t seed) {
    IrregularWaves w;
    const double fp = 1.0 / tp;
    const int per_peak = count / 2; // steps of df between 0 and fp
    const double df = fp / per_peak;
    w.frequency_step = df;
    const int first = (per_peak + 1) / 2; // 0.5 fp (rounded up)
    double variance = 0.0;
    for (int j = first; j < first + count; ++j) {
        const double f = j * df;
        const double s = jonswap_shape(f, fp, gamma);
        w.frequency.push_back(f);
        w.amplitude.push_back(std::sqrt(2.0 * s * df));
        variance += s * df;
    }
    // Hm0 = 4 sqrt(m0) with m0 = sum a^2 / 2.
    const double scale = hs / (4.0 * std::sqrt(variance));
    for (double &a : w.amplitude)
        a *= scale;
    w.shape_scale = scale * scale;
    // Phases from the 53 high bits of a 64-bit Mersenne twister: the same
    // seed gives the same train with any standard library.
    std::mt19937_64 rng(seed);
    for (std::size_t j = 0; j < w.frequency.size(); ++j)
        w.phase.push_back(2.0 * M_PI * static_cast<double>(rng() >> 11) * 0x1.0p-53);
    return w;
}

IrregularWaves jonswap_components(const JonswapSea &sea) {
    return jonswap_components(sea.hs, sea.tp, sea.gamma, sea.components, sea.seed);
}

double target_tm02(const IrregularWaves &waves) {
    double m0 = 0.0, m2 = 0.0;
    for (std::size_t j = 0; j < waves.frequency.size(); ++j) {
        const double e = 0.5 * waves.amplitude[j] * waves.amplitude[j];
        m0 += e;
        m2 += e * waves.frequency[j] * waves.frequency[j];
    }
    return m2 > 0.0 ? std::sqrt(m0 / m2) : 0.0;
}

} // namespace armour
