#include "wave_theory.h"

#include <cmath>
#include <cstdio>

namespace armour {

double wave_number(double period, double depth, double g) {
    const double omega = 2.0 * M_PI / period;
    const double k_deep = omega * omega / g;
    // Start from the shallow or deep limit, whichever is larger: Newton on
    // f(k) = g k tanh(kh) - omega^2 then converges monotonically.
    double k = std::max(k_deep, omega / std::sqrt(g * depth));
    for (int i = 0; i < 100; ++i) {
        const double t = std::tanh(k * depth);
        const double f = g * k * t - omega * omega;
        const double df = g * (t + k * depth * (1.0 - t * t));
        const double step = f / df;
        k -= step;
        if (std::abs(step) < 1e-14 * k)
            break;
    }
    return k;
}

double wavelength(double period, double depth, double g) {
    return 2.0 * M_PI / wave_number(period, depth, g);
}

double group_velocity(double period, double depth, double g) {
    const double k = wave_number(period, depth, g), kh2 = 2.0 * k * depth;
    return 0.5 * (2.0 * M_PI / period / k) * (1.0 + kh2 / std::sinh(kh2));
}

double ursell_number(double height, double period, double depth, double g) {
    const double L = wavelength(period, depth, g);
    return height * L * L / (depth * depth * depth);
}

double miche_height(double period, double depth, double g) {
    const double k = wave_number(period, depth, g);
    return kMicheSteepness * (2.0 * M_PI / k) * std::tanh(k * depth);
}

std::string regular_theory(const std::string &theory, double height, double period, double depth, double g) {
    if (theory != "auto")
        return theory;
    const double ur = ursell_number(height, period, depth, g);
    const double kh = wave_number(period, depth, g) * depth;
    if (ur > kStokesIIUrsellLimit && kh < M_PI / 4)
        return "cnoidal";
    const double deep_wavelength = g * period * period / (2.0 * M_PI);
    return height / deep_wavelength > kStokesVSteepness ? "StokesV" : "StokesII";
}

std::string regular_wave_refusal(const std::string &theory, double height, double period, double depth,
                                 double g) {
    char buf[320];
    if (height / depth > kDepthBreakingRatio) {
        std::snprintf(buf, sizeof buf, "H / h = %.3g > %.2g: the wave breaks at the inlet (depth limit)",
                      height / depth, kDepthBreakingRatio);
        return buf;
    }
    const double hmax = miche_height(period, depth, g);
    if (height > hmax) {
        std::snprintf(buf, sizeof buf,
                      "H = %.4g m > %.4g m = 0.142 L tanh(kh): the wave breaks at the inlet (Miche's "
                      "steepness limit, L = %.4g m)",
                      height, hmax, wavelength(period, depth, g));
        return buf;
    }
    const double ur = ursell_number(height, period, depth, g);
    const double kh = wave_number(period, depth, g) * depth;
    if ((theory == "StokesII" || theory == "StokesV") && ur > kStokesIIUrsellLimit) {
        std::snprintf(buf, sizeof buf,
                      "Ursell number H L^2 / h^3 = %.3g > 8 pi^2 / 3 = 26.3: %s makes a secondary crest in "
                      "the trough; use theory \"cnoidal\" (or a deeper flume, or a shorter period)",
                      ur, theory.c_str());
        return buf;
    }
    if (theory == "cnoidal" && (ur <= kStokesIIUrsellLimit || kh >= M_PI / 4)) {
        std::snprintf(buf, sizeof buf,
                      "cnoidal theory needs shallow water: Ursell number %.3g (must be > 26.3) and kh = %.3g "
                      "(must be < pi/4, h/L < 1/8); use theory \"StokesII\" or \"StokesV\"",
                      ur, kh);
        return buf;
    }
    if (theory == "StokesII" && kh < kStockWavelengthMinKh) {
        std::snprintf(buf, sizeof buf,
                      "kh = %.3g < %.2g: OpenFOAM v1912's StokesII finds the wavelength by a fixed-point "
                      "iteration that has not converged there; use theory \"cnoidal\" or \"StokesV\"",
                      kh, kStockWavelengthMinKh);
        return buf;
    }
    if (theory == "streamFunction")
        return "theory \"streamFunction\": OpenFOAM v1912's model solves nothing, it reads Fenton's (1988) "
               "Fourier solution (waveLength, uMean and the coefficients Bjs, Ejs) from waveProperties, and "
               "armour "
               "has no solver for it; use \"StokesII\", \"StokesV\", \"cnoidal\" or \"auto\"";
    return "";
}

} // namespace armour
