// libarmourWaves end to end: foam_cases/solitary_flume (2D interFoam flume,
// h = 0.3 m, H = 0.09 m, 200 x 45 cells) through foam_cases/run_case.sh,
// with the surface elevation at two gauges checked against Boussinesq
// solitary wave theory, and the absorbing outlet against a wall; the gauges
// in still water (tests/foam_cases/gauge_tank) on faces and over a cut-out solid.
// Needs Debian's openfoam (the target exists only then). docs/waves.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

// foam_cases/solitary_flume: 0/U, 0/alpha.water.orig, constant/g, controlDict.
constexpr double kDepth = 0.3;   // h, m
constexpr double kHeight = 0.09; // H = 0.3 h, m
constexpr double kG = 9.81;
constexpr double kX1 = 1.515; // gauges, m downstream of the inlet
constexpr double kX2 = 4.515;
constexpr double kOutlet = 6.0;
constexpr double kEndTime = 8.5;

const double kK = std::sqrt(0.75 * kHeight / (kDepth * kDepth * kDepth)); // 1.581 1/m
const double kC = std::sqrt(kG * (kDepth + kHeight));                     // 1.956 m/s
// The BCs' default crestTime: eta(inlet, 0) = 1e-3 H.
const double kCrestTime = std::acosh(std::sqrt(1000.0)) / (kK * kC); // 1.341 s

struct CaseRun {
    int status = -1;
    std::string output;
    fs::path dir;
};

struct Gauges {
    std::vector<double> t, eta1, eta2; // elevation above still water
};

struct Crest {
    double t = NAN, eta = NAN;
};

std::string slurp(const fs::path &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// wall_outlet: the same flume with a no-slip wall instead of the absorbing
// outlet, the control for the absorption check.
CaseRun run_flume(const std::string &name, bool wall_outlet) {
    CaseRun r;
    std::string tmpl = (fs::temp_directory_path() / ("armour_test_waves_" + name + "_XXXXXX")).string();
    if (!mkdtemp(tmpl.data()))
        return r;
    r.dir = tmpl;
    fs::path source = fs::path(ARMOUR_SOURCE_DIR) / "foam_cases/solitary_flume";
    if (wall_outlet) {
        const fs::path copy = r.dir / "template";
        fs::copy(source, copy, fs::copy_options::recursive);
        std::string u = slurp(copy / "0/U");
        const auto begin = u.find("    outlet\n");
        const auto end = u.find("    }\n", begin);
        if (begin == std::string::npos || end == std::string::npos)
            return r;
        u.replace(begin, end + 6 - begin, "    outlet\n    {\n        type            noSlip;\n    }\n");
        std::ofstream(copy / "0/U") << u;
        source = copy;
    }
    const fs::path log = r.dir / "run_case.log";
    const std::string cmd = std::string("bash '") + ARMOUR_SOURCE_DIR + "/foam_cases/run_case.sh' --waves '" +
                            ARMOUR_WAVES_LIB + "' '" + source.string() + "' '" + (r.dir / "case").string() +
                            "' > '" + log.string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    r.output = slurp(log);
    return r;
}

Gauges read_gauges(const fs::path &case_dir) {
    Gauges g;
    std::ifstream in(case_dir / "postProcessing/gauges/0/surfaceElevation.dat");
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream s(line);
        double t, z1, z2;
        if (s >> t >> z1 >> z2) {
            g.t.push_back(t);
            g.eta1.push_back(z1 - kDepth);
            g.eta2.push_back(z2 - kDepth);
        }
    }
    return g;
}

// The highest sample refined by the parabola through it and its neighbours:
// the step (~0.01 s) is a fiftieth of the crest passage.
Crest crest(const std::vector<double> &t, const std::vector<double> &eta) {
    Crest c;
    if (eta.size() < 3)
        return c;
    std::size_t i = std::max_element(eta.begin(), eta.end()) - eta.begin();
    i = std::clamp<std::size_t>(i, 1, eta.size() - 2);
    const double t0 = t[i - 1], t1 = t[i], t2 = t[i + 1];
    const double y0 = eta[i - 1], y1 = eta[i], y2 = eta[i + 1];
    const double d = (t0 - t1) * (t0 - t2) * (t1 - t2);
    const double a = (t2 * (y1 - y0) + t1 * (y0 - y2) + t0 * (y2 - y1)) / d;
    const double b = (t2 * t2 * (y0 - y1) + t1 * t1 * (y2 - y0) + t0 * t0 * (y1 - y2)) / d;
    const double cc = (t1 * t2 * (t1 - t2) * y0 + t2 * t0 * (t2 - t0) * y1 + t0 * t1 * (t0 - t1) * y2) / d;
    c.t = -b / (2 * a);
    c.eta = a * c.t * c.t + b * c.t + cc;
    return c;
}

// How long eta stays above half its peak (linear interpolation between samples).
double half_height_duration(const std::vector<double> &t, const std::vector<double> &eta, double peak) {
    const std::size_t i = std::max_element(eta.begin(), eta.end()) - eta.begin();
    std::size_t a = i, b = i;
    while (a > 0 && eta[a] > peak / 2)
        --a;
    while (b + 1 < eta.size() && eta[b] > peak / 2)
        ++b;
    auto cross = [&](std::size_t lo, std::size_t hi) {
        return t[lo] + (peak / 2 - eta[lo]) * (t[hi] - t[lo]) / (eta[hi] - eta[lo]);
    };
    return cross(b - 1, b) - cross(a, a + 1);
}

// Largest |eta| at a gauge within [from, to).
double max_abs(const Gauges &g, const std::vector<double> &eta, double from, double to) {
    double m = 0;
    for (std::size_t i = 0; i < g.t.size(); ++i)
        if (g.t[i] >= from && g.t[i] < to)
            m = std::max(m, std::abs(eta[i]));
    return m;
}

// Time-weighted mean of eta from `from` to the end (trapezoids).
double mean(const Gauges &g, const std::vector<double> &eta, double from) {
    double area = 0, span = 0;
    for (std::size_t i = 1; i < g.t.size(); ++i)
        if (g.t[i - 1] >= from) {
            const double dt = g.t[i] - g.t[i - 1];
            area += dt * (eta[i] + eta[i - 1]) / 2;
            span += dt;
        }
    return span > 0 ? area / span : NAN;
}

// One run checked for everything: CTest runs each TEST in its own process,
// so a shared fixture would rerun the flume (~17 s) for every check.
TEST(SolitaryFlume, MatchesTheoryAndOutletAbsorbs) {
    const CaseRun run = run_flume("absorbing", false);
    ASSERT_EQ(run.status, 0) << run.output;
    const Gauges g = read_gauges(run.dir / "case");
    ASSERT_GT(g.t.size(), 100u);
    EXPECT_NEAR(g.t.back(), kEndTime, 0.05);
    const Crest c1 = crest(g.t, g.eta1);
    const Crest c2 = crest(g.t, g.eta2);

    // Crest height. Generation: 5 h from the inlet the wave must still be
    // the one imposed; measured 0.0897 m (-0.3 %; +0.9 % on a mesh twice as
    // fine) at 1.515 m; 5 % allows for numerical damping on 10 cells per h
    // and ~9 per H. Gauge 2, 3 m further: measured 0.0864 m (-4.0 %; -2.9 %
    // twice as fine). The loss between the gauges, 3.7 %, is the same on
    // both meshes: it is the first-order wave adjusting to the Navier-Stokes
    // equations (shedding a small tail) plus bed friction, not mesh damping
    // (docs/waves.md). 10 % covers it and still fails a wrong inlet flux (the
    // generated height follows the imposed flux u (h + eta) = c eta).
    EXPECT_NEAR(c1.eta, kHeight, 0.05 * kHeight) << "gauge 1 crest at t = " << c1.t;
    EXPECT_NEAR(c2.eta, kHeight, 0.10 * kHeight) << "gauge 2 crest at t = " << c2.t;
    // Damping, not growth: the wave does not steepen into a bore here.
    EXPECT_LE(c2.eta, c1.eta * 1.01);

    // Celerity between the gauges against c = sqrt(g (h + H)) = 1.956 m/s.
    // Measured 1.916 m/s (-2.1 %), the same on a mesh twice as fine, so not
    // mesh dispersion: the wave is lower than H between the gauges (c falls
    // with H) and first-order theory overestimates c (second order,
    // Laitone: 1.950 m/s). 5 % is the brief's bound.
    ASSERT_GT(c2.t, c1.t);
    const double celerity = (kX2 - kX1) / (c2.t - c1.t);
    EXPECT_NEAR(celerity / kC, 1.0, 0.05) << "celerity " << celerity << " m/s, theory " << kC << " m/s";

    // Placement: the crest passes the inlet at crestTime and gauge 1 x1/c
    // later (theory 2.115 s, measured 2.141 s: 0.03 s is 1.7 % of the
    // travel time). Shape: above H/2 for 2 acosh(sqrt 2)/(k c) = 0.570 s
    // (measured 0.588 s, +3 %); 10 % catches a wrong k (width ~ 1/sqrt(H)).
    EXPECT_NEAR(c1.t, kCrestTime + kX1 / kC, 0.1);
    const double width = half_height_duration(g.t, g.eta1, c1.eta);
    const double width_theory = 2 * std::acosh(std::sqrt(2.0)) / (kK * kC);
    EXPECT_NEAR(width / width_theory, 1.0, 0.10)
        << "measured " << width << " s, theory " << width_theory << " s";

    // The outlet absorbs. After the incident wave has passed gauge 1 (its
    // crest + 3/(k c), where eta < 1 % H) and until the end (before anything
    // re-reflected at the inlet could be back, ~8.8 s), gauge 1 sees only
    // what came back from the outlet. Theory for the nonlinear condition:
    // reflected <= 1.2 % H (header of the BC); measured 2.9 % H, the rest is
    // the coarse mesh's trailing ripple. Bound 10 % H; the same flume with a
    // wall there measures 90 % H (WallOutletReflects), so the check cannot
    // pass by accident.
    const double from = c1.t + 3.0 / (kK * kC);
    ASSERT_LT(from, c1.t + 2 * (kOutlet - kX1) / kC) << "window would start after the reflection";
    const double reflected = max_abs(g, g.eta1, from, kEndTime + 1);
    EXPECT_LT(reflected, 0.10 * kHeight) << "reflected " << reflected << " m";
    // The wave's volume (2 H / k = 0.114 m^2, +1.9 cm = 21 % H over the
    // flume if kept) has left: the mean level over the last 2.5 s is h
    // within 3 % H (measured +0.5 % and -0.1 % H; 39 % H at gauge 1 with
    // the wall).
    EXPECT_LT(std::abs(mean(g, g.eta1, 6.0)), 0.03 * kHeight);
    EXPECT_LT(std::abs(mean(g, g.eta2, 6.0)), 0.03 * kHeight);

    // Kept on failure for the logs and the gauge record.
    if (!HasFailure())
        fs::remove_all(run.dir);
}

// Control: with a wall at the outlet the same window sees the reflected
// wave (about H), so the absorption check measures the outlet, not the
// window.
TEST(SolitaryFlume, WallOutletReflects) {
    const CaseRun wall = run_flume("wall", true);
    ASSERT_EQ(wall.status, 0) << wall.output;
    const Gauges g = read_gauges(wall.dir / "case");
    const Crest c1 = crest(g.t, g.eta1);
    const double reflected = max_abs(g, g.eta1, c1.t + 3.0 / (kK * kC), kEndTime + 1);
    EXPECT_GT(reflected, 0.7 * kHeight) << "reflected " << reflected << " m";
    EXPECT_GT(mean(g, g.eta1, 6.0), 0.1 * kHeight);
    if (!HasFailure())
        fs::remove_all(wall.dir);
}

// tests/foam_cases/gauge_tank: still water at 0.40 m (a mesh face, so alpha is
// exactly 0 or 1) in 12 cells across, whose mid plane y = 0 blockMesh puts
// at +-1e-18, around a solid box cut out at x 0.1..0.2, z 0.1..0.2. Every
// gauge must read the still-water level: on the rounded face (read 0.44 m
// before the fix, layers counted twice), over the box (0.32 and 0.30 m: the
// box's height was missing), on block faces, off faces, and on the domain's
// far corner (was "outside the mesh", and the gauges silently dropped).
TEST(WaveGauges, StillWaterOnFacesAndOverACutOutSolid) {
    std::string tmpl = (fs::temp_directory_path() / "armour_test_gauges_XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    const fs::path dir = tmpl;
    const fs::path log = dir / "run_case.log";
    const std::string cmd = std::string("bash '") + ARMOUR_SOURCE_DIR + "/foam_cases/run_case.sh' --waves '" +
                            ARMOUR_WAVES_LIB + "' '" + ARMOUR_SOURCE_DIR + "/tests/foam_cases/gauge_tank' '" +
                            (dir / "case").string() + "' > '" + log.string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << slurp(log);

    std::ifstream in(dir / "case/postProcessing/gauges/0/surfaceElevation.dat");
    std::string line;
    std::vector<double> first;
    while (first.empty() && std::getline(in, line)) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream s(line);
        double v;
        s >> v; // time
        while (s >> v)
            first.push_back(v);
    }
    constexpr double kLevel = 0.40; // m
    ASSERT_EQ(first.size(), 6U) << "gauge record missing (" << dir << ")";
    for (std::size_t i = 0; i < first.size(); ++i)
        EXPECT_NEAR(first[i], kLevel, 1e-6) << "gauge " << i + 1;
    if (!HasFailure())
        fs::remove_all(dir);
}

} // namespace
