#include "wave_separation.h"

#include "wave_theory.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <numeric>
#include <stdexcept>

namespace armour {

namespace {

using Complex = std::complex<double>;

struct Pair {
    Complex incident, reflected;
    bool resolved = true;
};

// Least squares of B_p = Z_I e^{-ikx_p} + Z_R e^{ikx_p}: the normal matrix is
// [[P, S], [conj S, P]], S = sum e^{2ikx_p}.
Pair least_squares(const std::vector<double> &x, const std::vector<Complex> &b, double k) {
    const double p = static_cast<double>(x.size());
    Complex s = 0.0, rhs_i = 0.0, rhs_r = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const Complex e = std::polar(1.0, k * x[i]); // e^{ikx}
        s += e * e;
        rhs_i += e * b[i];            // conj(e^{-ikx}) b
        rhs_r += std::conj(e) * b[i]; // conj(e^{ikx}) b
    }
    Pair out;
    const double det = p * p - std::norm(s);
    out.resolved = det > 0.05 * p * p;
    if (det <= 1e-12 * p * p)
        return out;
    out.incident = (p * rhs_i - s * rhs_r) / det;
    out.reflected = (p * rhs_r - std::conj(s) * rhs_i) / det;
    return out;
}

// Complex amplitude of eta at omega: least squares of c0 + a cos + b sin.
Complex fitted_amplitude(const std::vector<double> &eta, double dt, double omega) {
    double m[3][3] = {}, r[3] = {};
    for (std::size_t n = 0; n < eta.size(); ++n) {
        const double t = static_cast<double>(n) * dt;
        const double basis[3] = {1.0, std::cos(omega * t), std::sin(omega * t)};
        for (int i = 0; i < 3; ++i) {
            r[i] += basis[i] * eta[n];
            for (int j = 0; j < 3; ++j)
                m[i][j] += basis[i] * basis[j];
        }
    }
    // Gaussian elimination on the 3 x 3 normal equations.
    for (int c = 0; c < 3; ++c)
        for (int row = c + 1; row < 3; ++row) {
            const double f = m[row][c] / m[c][c];
            for (int j = c; j < 3; ++j)
                m[row][j] -= f * m[c][j];
            r[row] -= f * r[c];
        }
    double sol[3];
    for (int i = 2; i >= 0; --i) {
        double acc = r[i];
        for (int j = i + 1; j < 3; ++j)
            acc -= m[i][j] * sol[j];
        sol[i] = acc / m[i][i];
    }
    return {sol[1], -sol[2]}; // a cos wt + b sin wt = Re((a - ib) e^{iwt})
}

void fill_unresolved(std::vector<double> &density, const std::vector<bool> &resolved) {
    const std::size_t n = density.size();
    for (std::size_t j = 0; j < n; ++j) {
        if (resolved[j])
            continue;
        std::size_t lo = j, hi = j;
        while (lo > 0 && !resolved[lo])
            --lo;
        while (hi + 1 < n && !resolved[hi])
            ++hi;
        const bool has_lo = resolved[lo], has_hi = resolved[hi];
        if (has_lo && has_hi)
            density[j] = density[lo] + (density[hi] - density[lo]) * static_cast<double>(j - lo) /
                                           static_cast<double>(hi - lo);
        else if (has_lo || has_hi)
            density[j] = density[has_lo ? lo : hi];
    }
}

void check(const GaugeArray &g) {
    if (g.x.size() < 3 || g.eta.size() != g.x.size())
        throw std::invalid_argument("wave separation: needs at least three gauges, one record each");
    for (const auto &e : g.eta)
        if (e.size() != g.eta[0].size() || e.size() < 8)
            throw std::invalid_argument("wave separation: records of equal length (>= 8 samples) needed");
    if (!(g.dt > 0.0))
        throw std::invalid_argument("wave separation: dt must be > 0");
}

} // namespace

SeparatedWaves separate_waves(const GaugeArray &gauges, double depth, double g, double f_min, double f_max) {
    check(gauges);
    const std::size_t n = gauges.eta[0].size();
    const double duration = static_cast<double>(n) * gauges.dt;
    const double df = 1.0 / duration;
    SeparatedWaves out;
    const auto first = static_cast<std::size_t>(std::max(1.0, std::ceil(f_min / df - 1e-9)));
    const auto last = std::min(static_cast<std::size_t>(std::floor(f_max / df + 1e-9)), (n - 1) / 2);
    std::vector<Complex> b(gauges.x.size());
    for (std::size_t j = first; j <= last; ++j) {
        const double f = static_cast<double>(j) * df;
        double measured = 0.0;
        for (std::size_t p = 0; p < gauges.x.size(); ++p) {
            // DFT bin j: B = (2/n) sum eta_m e^{-i 2 pi j m / n}.
            Complex sum = 0.0;
            const double step = -2.0 * M_PI * static_cast<double>(j) / static_cast<double>(n);
            for (std::size_t m = 0; m < n; ++m)
                sum += gauges.eta[p][m] * std::polar(1.0, step * static_cast<double>(m % n));
            b[p] = 2.0 * sum / static_cast<double>(n);
            measured += 0.5 * std::norm(b[p]) / df;
        }
        const Pair z = least_squares(gauges.x, b, wave_number(1.0 / f, depth, g));
        out.frequency.push_back(f);
        out.incident.push_back(0.5 * std::norm(z.incident) / df);
        out.reflected.push_back(0.5 * std::norm(z.reflected) / df);
        out.measured.push_back(measured / static_cast<double>(gauges.x.size()));
        out.resolved.push_back(z.resolved);
    }
    fill_unresolved(out.incident, out.resolved);
    fill_unresolved(out.reflected, out.resolved);
    return out;
}

SpectralParameters spectral_parameters(const std::vector<double> &frequency,
                                       const std::vector<double> &density, double f_min, double f_max) {
    SpectralParameters s;
    if (frequency.size() < 2)
        return s;
    const double df = frequency[1] - frequency[0];
    double m_minus1 = 0.0, m2 = 0.0, peak = -1.0;
    for (std::size_t j = 0; j < frequency.size(); ++j) {
        const double f = frequency[j];
        if (f < f_min - 1e-9 * df || f > f_max + 1e-9 * df)
            continue;
        s.m0 += density[j] * df;
        m_minus1 += density[j] * df / f;
        m2 += density[j] * df * f * f;
        if (density[j] > peak) {
            peak = density[j];
            s.tp = 1.0 / f;
        }
    }
    s.hm0 = 4.0 * std::sqrt(s.m0);
    s.tm10 = s.m0 > 0.0 ? m_minus1 / s.m0 : 0.0;
    s.tm02 = m2 > 0.0 ? std::sqrt(s.m0 / m2) : 0.0;
    return s;
}

RegularSeparation separate_regular(const GaugeArray &gauges, double period, double depth, double g) {
    check(gauges);
    const double omega = 2.0 * M_PI / period;
    std::vector<Complex> b;
    for (const auto &eta : gauges.eta)
        b.push_back(fitted_amplitude(eta, gauges.dt, omega));
    const Pair z = least_squares(gauges.x, b, wave_number(period, depth, g));
    if (!z.resolved)
        throw std::invalid_argument("wave separation: the gauge spacing cannot separate waves of this period "
                                    "(all spacings near a multiple of half a wavelength)");
    RegularSeparation r;
    r.incident_height = 2.0 * std::abs(z.incident);
    r.reflected_height = 2.0 * std::abs(z.reflected);
    r.reflection = r.incident_height > 0.0 ? r.reflected_height / r.incident_height : 0.0;
    return r;
}

ZeroCrossing zero_down_crossing(const std::vector<double> &eta, double dt, double min_height) {
    ZeroCrossing z;
    std::vector<double> crossings; // s, interpolated
    for (std::size_t i = 1; i < eta.size(); ++i)
        if (eta[i - 1] >= 0.0 && eta[i] < 0.0)
            crossings.push_back((static_cast<double>(i - 1) + eta[i - 1] / (eta[i - 1] - eta[i])) * dt);
    double heights = 0.0, periods = 0.0;
    for (std::size_t c = 1; c < crossings.size(); ++c) {
        const auto a = static_cast<std::size_t>(std::ceil(crossings[c - 1] / dt));
        const auto b = static_cast<std::size_t>(std::floor(crossings[c] / dt));
        if (b <= a)
            continue;
        const auto [lo, hi] =
            std::minmax_element(eta.begin() + static_cast<long>(a), eta.begin() + static_cast<long>(b) + 1);
        const double h = *hi - *lo;
        if (h < min_height)
            continue;
        heights += h;
        z.heights.push_back(h);
        periods += crossings[c] - crossings[c - 1];
        ++z.waves;
    }
    if (z.waves > 0) {
        z.mean_height = heights / z.waves;
        z.mean_period = periods / z.waves;
    }
    return z;
}

WaveStatistics wave_statistics(std::vector<double> eta, double dt, double min_height) {
    WaveStatistics w;
    if (eta.empty())
        return w;
    const double n = static_cast<double>(eta.size());
    for (const double e : eta)
        w.mean_level += e / n;
    double m0 = 0.0;
    for (double &e : eta) {
        e -= w.mean_level;
        m0 += e * e / n;
    }
    w.hm0 = 4.0 * std::sqrt(m0);
    const ZeroCrossing z = zero_down_crossing(eta, dt, min_height);
    w.waves = z.waves;
    std::vector<double> h = z.heights;
    std::sort(h.begin(), h.end(), std::greater<>());
    if (!h.empty())
        w.h_max = h.front();
    if (const std::size_t third = h.size() / 3; third > 0)
        w.h_one_third = std::accumulate(h.begin(), h.begin() + static_cast<long>(third), 0.0) /
                        static_cast<double>(third);
    // Highest first, h[k] is exceeded by k waves: k = 2 % of them, rounded
    // up (N = 50: the second highest; under 50 no height is exceeded by so few).
    if (h.size() >= 50)
        w.h_2_percent = h[static_cast<std::size_t>(std::ceil(0.02 * static_cast<double>(h.size())))];
    return w;
}

std::vector<double> resample(const std::vector<double> &t, const std::vector<double> &y, double t0, double dt,
                             std::size_t n) {
    std::vector<double> out(n, 0.0);
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double ti = t0 + static_cast<double>(i) * dt;
        while (k + 2 < t.size() && t[k + 1] < ti)
            ++k;
        if (t.size() < 2) {
            out[i] = y.empty() ? 0.0 : y[0];
            continue;
        }
        const double w = std::clamp((ti - t[k]) / (t[k + 1] - t[k]), 0.0, 1.0);
        out[i] = y[k] + w * (y[k + 1] - y[k]);
    }
    return out;
}

} // namespace armour
