// Sphere clumps: union integrals, the evaluator on cases with known answers,
// and the behaviour of both builders.
#include "clump_evaluator.h"
#include "clump_io.h"
#include "clump_methods.h"
#include "clump_support.h"
#include "shape_query.h"
#include "shapes.h"
#include "stl_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

using namespace armour;

namespace {

constexpr double kPi = 3.14159265358979323846;

double sphere_volume(double r) {
    return 4.0 / 3.0 * kPi * r * r * r;
}

const Shape &unit_cube() {
    static const Shape cube = make_cube_shape(1.0, 0.0, 1000.0);
    return cube;
}

const Shape &dolos() {
    static const Shape shape = make_dolos_shape(2.0, kDolosWaistDefault, 2400.0);
    return shape;
}

} // namespace

TEST(ClumpVolume, SingleSphereMatchesFormula) {
    const Clump one = {{Eigen::Vector3d(0.3, -0.2, 0.1), 0.7}};
    EXPECT_NEAR(clump_volume(one), sphere_volume(0.7), 1e-4 * sphere_volume(0.7));
}

TEST(ClumpVolume, OverlapIsCountedOnce) {
    // Two equal spheres at centre distance d overlap in a lens of volume
    // pi (4R + d)(2R - d)^2 / 12.
    const double R = 0.5, d = 0.6;
    const Clump two = {{Eigen::Vector3d(0, 0, 0), R}, {Eigen::Vector3d(d, 0, 0), R}};
    const double lens = kPi * (4 * R + d) * (2 * R - d) * (2 * R - d) / 12.0;
    const double expected = 2 * sphere_volume(R) - lens;
    EXPECT_NEAR(clump_volume(two), expected, 2e-4 * expected);
}

TEST(ClumpVolume, SphereInertiaIsTwoFifthsMR2) {
    const double r = 0.4, density = 2400.0;
    const MassProperties p = clump_mass_properties({{Eigen::Vector3d(1, 2, 3), r}}, density);
    const double m = density * sphere_volume(r);
    EXPECT_NEAR(p.mass, m, 1e-4 * m);
    EXPECT_NEAR((p.centroid - Eigen::Vector3d(1, 2, 3)).norm(), 0.0, 1e-6);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(p.inertia(k, k), 0.4 * m * r * r, 1e-3 * 0.4 * m * r * r);
    EXPECT_NEAR(p.inertia(0, 1), 0.0, 1e-6 * m * r * r);
}

TEST(ClumpVolume, DisjointSpheresCentroidIsMassWeighted) {
    const Clump two = {{Eigen::Vector3d(0, 0, 0), 0.2}, {Eigen::Vector3d(1, 0, 0), 0.4}};
    const MassProperties p = clump_mass_properties(two, 1.0);
    const double w = sphere_volume(0.4) / (sphere_volume(0.2) + sphere_volume(0.4));
    EXPECT_NEAR(p.centroid.x(), w, 1e-4);
}

TEST(ClumpEvaluator, InscribedSphereInCubeHasKnownErrors) {
    // A unit cube represented by its inscribed sphere (r = a/2): every error is analytic.
    const Clump ball = {{Eigen::Vector3d::Zero(), 0.5}};
    const ClumpQuality q = evaluate_clump(unit_cube(), ball);
    EXPECT_NEAR(q.volume_error, kPi / 6.0 - 1.0, 1e-4);
    EXPECT_NEAR(q.centroid_offset, 0.0, 1e-6);
    // I_sphere = (2/5) (rho pi/6) (1/4) = rho pi / 60; I_cube = rho / 6.
    EXPECT_NEAR(q.inertia_error, 1.0 - (kPi / 60.0) / (1.0 / 6.0), 1e-3);
    // Farthest exact point: a corner, sqrt(3)/2 - 1/2 from the sphere.
    EXPECT_NEAR(q.exact_to_clump.max, std::sqrt(3.0) / 2.0 - 0.5, 0.01);
    // Farthest sphere point: along a diagonal, 1/2 - 1/(2 sqrt(3)) from the faces.
    EXPECT_NEAR(q.clump_to_exact.max, 0.5 - 0.5 / std::sqrt(3.0), 0.005);
    EXPECT_GE(q.surface_max, q.exact_to_clump.max);
    EXPECT_GT(q.surface_rms, 0.0);
}

TEST(ClumpEvaluator, DistanceToUnionBoundaryIgnoresBuriedSurface) {
    // Two spheres overlapping along x. The point p = (0, 0, 0.2) lies inside
    // both; its radial projections onto each sphere fall inside the other, so
    // the nearest boundary point is on the seam circle (x = 0, radius
    // sqrt(R^2 - 0.25^2)), straight above p.
    const double R = 0.35;
    const Clump pair = {{Eigen::Vector3d(-0.25, 0, 0), R}, {Eigen::Vector3d(0.25, 0, 0), R}};
    const double seam = std::sqrt(R * R - 0.25 * 0.25);
    const std::vector<Eigen::Vector3d> points = {
        Eigen::Vector3d(0, 0, 0.2),   // inside, nearest point on the seam
        Eigen::Vector3d(-0.25, 0, 0), // a centre: nearest exposed point radially at R
        Eigen::Vector3d(0, 0, 0.6),   // outside: exact formula
    };
    const std::vector<double> d = distances_to_clump_surface(pair, points, 200000);
    EXPECT_NEAR(d[0], seam - 0.2, 0.004); // boundary-sample spacing bounds the error
    EXPECT_NEAR(d[1], R, 1e-12);
    EXPECT_NEAR(d[2], std::hypot(0.25, 0.6) - R, 1e-12);
}

// Rest gap (clump_evaluator.h): a unit cube with one sphere in each corner
// octant, centred at (+-1/4, +-1/4, +-1/4).
Clump corner_spheres(double r_even, double r_odd) {
    Clump clump;
    for (int i = 0; i < 8; ++i) {
        const bool odd = ((i & 1) + ((i >> 1) & 1) + ((i >> 2) & 1)) % 2 == 1;
        clump.push_back(
            {0.25 * Eigen::Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1), odd ? r_odd : r_even});
    }
    return clump;
}

TEST(ClumpRest, EqualCornerSpheresRestFlat) {
    // r = 1/4 touches all three faces of its octant: on every face four
    // spheres touch at once, around the centre.
    EXPECT_NEAR(rest_summary(unit_cube().mesh, Eigen::Vector3d::Zero(), corner_spheres(0.25, 0.25), 1.0).gap,
                0.0, 1e-12);
}

TEST(ClumpRest, AlternatingCornerSpheresRockByTheirRadiusStep) {
    // Radii alternate 0.25 / 0.2 over the corners (the optimised 8-sphere
    // cube's pattern): on each face two diagonal spheres touch, the centre
    // lies on the line through them, and a third still leaves it on an edge;
    // only the fourth, 0.05 higher, surrounds it. Turning the whole unit
    // changes nothing.
    const Clump alternating = corner_spheres(0.25, 0.2);
    EXPECT_NEAR(rest_summary(unit_cube().mesh, Eigen::Vector3d::Zero(), alternating, 1.0).gap, 0.05, 1e-12);
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
    TriangleMesh mesh = unit_cube().mesh;
    for (Eigen::Vector3d &v : mesh.vertices)
        v = turn * v;
    Clump turned = alternating;
    for (Sphere &s : turned)
        s.center = turn * s.center;
    EXPECT_NEAR(rest_summary(mesh, Eigen::Vector3d::Zero(), turned, 1.0).gap, 0.05, 1e-9);
    // The quality report carries it as a fraction of Dn.
    EXPECT_NEAR(evaluate_clump(unit_cube(), alternating).rest_gap, 0.05, 1e-12);
}

TEST(ClumpRest, TipsOffFacesItCannotStandOn) {
    // Radii 0.25 / 0.1: the step, 0.15, is beyond rocking (kTippingGap = 0.1
    // of Dn): the four big spheres sit on the corners of a tetrahedron, and
    // the clump stands on three of them, tilted, not on any cube face.
    const RestSummary tetrahedral =
        rest_summary(unit_cube().mesh, Eigen::Vector3d::Zero(), corner_spheres(0.25, 0.1), 1.0);
    EXPECT_EQ(tetrahedral.faces, 6);
    EXPECT_EQ(tetrahedral.tipping_faces, 6);
    EXPECT_TRUE(std::isinf(tetrahedral.gap));
    // A single sphere rolls: no face, no finite gap.
    const RestSummary ball =
        rest_summary(unit_cube().mesh, Eigen::Vector3d::Zero(), {{Eigen::Vector3d::Zero(), 0.5}}, 1.0);
    EXPECT_EQ(ball.tipping_faces, 6);
    EXPECT_TRUE(std::isinf(ball.gap));
    // The alternating clump of 0.25 / 0.2 stands on all six.
    EXPECT_EQ(
        rest_summary(unit_cube().mesh, Eigen::Vector3d::Zero(), corner_spheres(0.25, 0.2), 1.0).tipping_faces,
        0);
}

// Topple angles (clump_support.h). A unit cube rests on all six faces; tilted
// towards any edge it topples at atan((a/2) / (a/2)) = 45 degrees.
TEST(ClumpTopple, CubeCornerSpheresToppleAtTheirContactPoints) {
    // Eight spheres of radius r touching the faces inside each corner: each
    // face stands on four, whose touching points are a/2 - r from the centre
    // line, at height a/2: tan(theta) = (1/2 - r) / (1/2).
    const double r = 0.1;
    Clump inside;
    for (int i = 0; i < 8; ++i)
        inside.push_back({(0.5 - r) * Eigen::Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1), r});
    const auto faces = topple_angles(unit_cube().mesh, Eigen::Vector3d::Zero(), inside, 1.0);
    ASSERT_EQ(faces.size(), 6u);
    const double expected = std::atan((0.5 - r) / 0.5) * 180.0 / kPi; // 38.66 deg
    for (const FaceTopple &f : faces) {
        ASSERT_EQ(f.exact_deg.size(), 4u);
        EXPECT_EQ(f.clump_supports.size(), 4u);
        for (std::size_t e = 0; e < 4; ++e) {
            EXPECT_NEAR(f.exact_deg[e], 45.0, 1e-9);
            EXPECT_NEAR(f.clump_deg[e], expected, 1e-9);
        }
    }
    EXPECT_NEAR(topple_error_deg(unit_cube().mesh, Eigen::Vector3d::Zero(), inside, 1.0), 45.0 - expected,
                1e-9);
    EXPECT_NEAR(evaluate_clump(unit_cube(), inside).topple_error_deg, 45.0 - expected, 1e-9);
    // Centred on the corners instead: the touching points are the exact
    // corners, but the plane is r lower: tan(theta) = (1/2) / (1/2 + r).
    Clump on_corners = inside;
    for (Sphere &s : on_corners)
        s.center = s.center / (0.5 - r) * 0.5;
    EXPECT_NEAR(topple_error_deg(unit_cube().mesh, Eigen::Vector3d::Zero(), on_corners, 1.0),
                45.0 - std::atan(0.5 / (0.5 + r)) * 180.0 / kPi, 1e-9);
    // A centre of mass off the middle: 0.1 towards +x, resting on -z, tilted
    // towards +x: (1/2 - 0.1 - r) / (1/2); towards -x: (1/2 + 0.1 - r) / (1/2).
    const Eigen::Vector3d off(0.1, 0.0, 0.0);
    for (const FaceTopple &f : topple_angles(unit_cube().mesh, off, inside, 1.0)) {
        if (f.normal.z() > -0.5)
            continue;
        std::vector<double> clump = f.clump_deg, exact = f.exact_deg;
        std::sort(clump.begin(), clump.end());
        std::sort(exact.begin(), exact.end());
        EXPECT_NEAR(clump.front(), std::atan((0.4 - r) / 0.5) * 180.0 / kPi, 1e-9);
        EXPECT_NEAR(clump.back(), std::atan((0.6 - r) / 0.5) * 180.0 / kPi, 1e-9);
        EXPECT_NEAR(exact.front(), std::atan(0.4 / 0.5) * 180.0 / kPi, 1e-9);
    }
}

TEST(ClumpTopple, RockingClumpTopplesAtZero) {
    // Radii alternating 0.25 / 0.2 (ClumpRest above): on each face two
    // diagonal spheres touch and the centre of mass lies on the line through
    // them: no tilt is needed to tip it.
    EXPECT_NEAR(topple_error_deg(unit_cube().mesh, Eigen::Vector3d::Zero(), corner_spheres(0.25, 0.2), 1.0),
                45.0, 1e-9);
}

TEST(ClumpTopple, TiltLeavesASlantedFaceThroughTheNearerEdge) {
    const std::vector<Eigen::Vector2d> square = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    EXPECT_NEAR(detail::exit_distance(square, {0, 0}, {1, 0}), 1.0, 1e-12);
    EXPECT_NEAR(detail::exit_distance(square, {0.5, 0}, {1, 0}), 0.5, 1e-12);
    EXPECT_NEAR(detail::exit_distance(square, {0, 0}, Eigen::Vector2d(1, 1).normalized()), std::sqrt(2.0),
                1e-12);
    EXPECT_EQ(detail::exit_distance(square, {2, 0}, {1, 0}), 0.0); // outside: no support
    // A slanted parallelogram (the dolos' fluke-to-fluke faces are like it):
    // its short edges y = +-1.2 lie beside the middle, not across from it,
    // so tilted towards them the foot leaves through a long edge, y = (x +
    // 2) 2/3 - 1.2, at y = 2/15; towards +x through y = (x + 1.6) 2/3 - 1.2
    // at x = 0.2.
    const std::vector<Eigen::Vector2d> slanted = {{-2, -1.2}, {-1.6, -1.2}, {2, 1.2}, {1.6, 1.2}};
    EXPECT_NEAR(detail::exit_distance(slanted, {0, 0}, {0, 1}), 2.0 / 15.0, 1e-12);
    EXPECT_NEAR(detail::exit_distance(slanted, {0, 0}, {1, 0}), 0.2, 1e-12);
}

TEST(ClumpTopple, OptimisedClumpsStandOnTheExactCorners) {
    // The default topple tolerance (1 degree) at the sphere counts the scenes
    // and the tolerance mode use (measured: cube 0.50 deg at N = 20, dolos
    // 0.89 deg at N = 59, docs/clump_builder.md).
    const ClumpTolerances defaults;
    const std::pair<const Shape *, int> cases[] = {{&unit_cube(), 20}, {&dolos(), 59}};
    for (const auto &[shape, n] : cases) {
        const Clump clump = build_clump(*shape, ClumpMethod::optimised, n);
        const auto corners =
            support_corners(resting_faces(shape->mesh, shape->props.centroid, shape->Dn()), shape->Dn());
        EXPECT_EQ(corners.size(), shape == &unit_cube() ? 8u : 40u);
        for (std::size_t k = 0; k < corners.size(); ++k)
            EXPECT_EQ(clump[k].radius, kSupportRadius * shape->Dn());
        const ClumpQuality q = evaluate_clump(*shape, clump);
        EXPECT_LE(q.topple_error_deg, defaults.topple_deg) << shape->kind;
        EXPECT_EQ(q.tipping_faces, 0) << shape->kind;
    }
    // Too few spheres for a corner each: no corner spheres, and it shows.
    EXPECT_GT(evaluate_clump(dolos(), build_clump(dolos(), ClumpMethod::optimised, 30)).topple_error_deg,
              10.0);
}

// Edge spheres (add_edge_supports): besides the corners, `per_edge` spheres
// evenly along every edge of every resting face, each reaching the plane the
// corner spheres reach on both of the edge's faces, out of the same count.
// The stability scene's 118-sphere clump with 3 per edge added (154 spheres:
// the same 110 body spheres) fits as well as the 118 (surface RMS within
// 0.05 % Dn, a tenth of the evaluator's resolution on the seams; measured
// 1.010 against 0.996 % Dn), matches the volume and stands like the unit.
// Asked for with too few spheres, or for the greedy clump, they are refused,
// never dropped.
TEST(ClumpSupport, EdgeSpheresStandEveryEdgeAsHighAsItsCorners) {
    const Shape cube = make_cube_shape(0.04, 0.0, 1540.0); // the stability scene's unit
    const double Dn = cube.Dn();
    const auto faces = resting_faces(cube.mesh, cube.props.centroid, Dn);
    auto supports = support_corners(faces, Dn);
    add_edge_supports(supports, faces, 3, Dn);
    ASSERT_EQ(supports.size(), 8u + 12u * 3u); // each of the 12 edges once, not once per face
    const Clump clump = build_clump(cube, ClumpMethod::optimised, 154, 1, 3);
    ASSERT_EQ(clump.size(), 154u);
    const RestingFace &first = faces[static_cast<std::size_t>(supports[0].faces[0])];
    const double reach = first.normal.dot(clump[0].center) + clump[0].radius - first.offset; // a corner's
    for (std::size_t k = 8; k < supports.size(); ++k) {
        ASSERT_EQ(supports[k].faces.size(), 2u);
        // Between two corners of its edge, a third of the way apart.
        int on_edge = 0;
        for (std::size_t c = 0; c < 8; ++c)
            on_edge += std::abs((supports[k].vertex - supports[c].vertex).norm() - 0.01) < 1e-12 ||
                       std::abs((supports[k].vertex - supports[c].vertex).norm() - 0.02) < 1e-12 ||
                       std::abs((supports[k].vertex - supports[c].vertex).norm() - 0.03) < 1e-12;
        EXPECT_GE(on_edge, 2) << k;
        EXPECT_EQ(clump[k].radius, kSupportRadius * Dn);
        for (int f : supports[k].faces)
            EXPECT_NEAR(faces[f].normal.dot(clump[k].center) + clump[k].radius - faces[f].offset, reach,
                        1e-12);
    }
    const ClumpQuality q = evaluate_clump(cube, clump);
    const ClumpQuality plain = evaluate_clump(cube, build_clump(cube, ClumpMethod::optimised, 118));
    EXPECT_LT(std::abs(q.volume_error), 1e-4);
    EXPECT_LT(q.surface_rms, plain.surface_rms + 0.0005);
    EXPECT_LE(q.topple_error_deg, ClumpTolerances{}.topple_deg);
    EXPECT_EQ(q.tipping_faces, 0);

    // A dolos's hull has edges from fluke to fluke across open air: no
    // sphere goes there (it would be a contact surface the unit lacks).
    // Measured: surface max 5.1 % Dn against 3.4 % without edge spheres
    // (the spheres on sharp hull edges sit out along their bisector, as the
    // corner spheres do); on a 0.2 m dolos 40-46 % while they were put in
    // the air too.
    const Clump dolos_edges = build_clump(dolos(), ClumpMethod::optimised, 200, 1, 1);
    EXPECT_LT(evaluate_clump(dolos(), dolos_edges).surface_max,
              evaluate_clump(dolos(), build_clump(dolos(), ClumpMethod::optimised, 200)).surface_max + 0.02);
    const double dolos_Dn = dolos().Dn();
    const auto dolos_faces = resting_faces(dolos().mesh, dolos().props.centroid, dolos_Dn);
    auto every_hull_edge = support_corners(dolos_faces, dolos_Dn);
    add_edge_supports(every_hull_edge, dolos_faces, 1, dolos_Dn);
    EXPECT_LT(static_cast<std::size_t>(fewest_spheres_with_edges(dolos(), 1) - 8), every_hull_edge.size());

    EXPECT_THROW(build_clump(cube, ClumpMethod::optimised, 51, 1, 3), InputError); // 44 + 8 needed
    EXPECT_NO_THROW(build_clump(cube, ClumpMethod::optimised, 52, 1, 3));
    EXPECT_THROW(build_clump(cube, ClumpMethod::greedy, 118, 1, 3), InputError);
    EXPECT_THROW(build_clump(cube, ClumpMethod::optimised, 118, 1, -1), InputError);
}

TEST(ClumpBuilders, AreDeterministicForASeed) {
    for (ClumpMethod method : {ClumpMethod::greedy, ClumpMethod::optimised, ClumpMethod::inscribed}) {
        const Clump a = build_clump(dolos(), method, 12, 7);
        const Clump b = build_clump(dolos(), method, 12, 7);
        ASSERT_EQ(a.size(), 12u);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            EXPECT_EQ(a[i].center, b[i].center);
            EXPECT_EQ(a[i].radius, b[i].radius);
        }
    }
}

TEST(ClumpBuilders, RejectFewerThanOneSphere) {
    EXPECT_THROW(build_clump(unit_cube(), ClumpMethod::optimised, 0), InputError);
    EXPECT_THROW(parse_method("voronoi"), InputError);
}

TEST(ClumpBuilders, GreedySpheresStayInside) {
    const Clump clump = build_clump(dolos(), ClumpMethod::greedy, 30, 3);
    const ShapeQuery query(dolos().mesh);
    for (const Sphere &s : clump) // an inscribed sphere's centre is at least r deep
        EXPECT_LE(query.signed_distance(s.center), -s.radius * (1 - 1e-12));
    EXPECT_LT(evaluate_clump(dolos(), clump).volume_error, 0.0);
}

// The inscribed clump (the optimised fit, each sphere shrunk inside) is what
// a layer the exact hulls settled at their own size hands over to: no sphere
// may reach out of a face, yet the clump must still stand on the exact
// face's corners (rest and topple as the unit) and keep its smallest body
// sphere at the optimiser's 3 % of Dn (else the DEM's step shrinks).
TEST(ClumpBuilders, InscribedSpheresStayInsideAndTheClumpStandsLikeTheUnit) {
    for (const Shape *shape : {&unit_cube(), &dolos()}) {
        const int n = 60; // enough for a corner sphere on every resting face's corner
        const Clump clump = build_clump(*shape, ClumpMethod::inscribed, n, 2);
        ASSERT_EQ(clump.size(), static_cast<std::size_t>(n));
        const ShapeQuery query(shape->mesh);
        double smallest_body = HUGE_VAL, body_reach = -HUGE_VAL, corner_reach = -HUGE_VAL;
        for (const Sphere &s : clump) {
            const double reach = query.signed_distance(s.center) + s.radius; // m beyond the surface
            const bool corner = s.radius < 0.02 * shape->Dn();               // the corner spheres: 0.01 Dn
            double &farthest = corner ? corner_reach : body_reach;
            farthest = std::max(farthest, reach);
            if (!corner)
                smallest_body = std::min(smallest_body, s.radius);
        }
        EXPECT_LE(body_reach, 1e-9 * shape->Dn()) << shape->kind; // no body sphere outside
        // The corner spheres sit on the convex hull's corners: inside a cube's
        // corners, on a dolos's up to their radius out (as in the optimised clump).
        EXPECT_LE(corner_reach, (shape->kind == "cube" ? 1e-9 : 0.01) * shape->Dn()) << shape->kind;
        EXPECT_GE(smallest_body, 0.03 * shape->Dn() * (1 - 1e-9)) << shape->kind;
        const ClumpQuality q = evaluate_clump(*shape, clump);
        const ClumpQuality opt = evaluate_clump(*shape, build_clump(*shape, ClumpMethod::optimised, n, 2));
        EXPECT_LT(q.rest_gap, 1e-9) << shape->kind;               // it rests on the exact face's plane
        EXPECT_LT(q.topple_error_deg, 1.0) << shape->kind;        // on its corners
        EXPECT_LT(q.volume_error, 0.0) << shape->kind;            // the price: it under-fills ...
        EXPECT_GT(q.surface_rms, opt.surface_rms) << shape->kind; // ... and fits worse
        std::printf(
            "[ inscribed] %s, %d spheres: volume %+.1f %%, surface RMS %.2f %% Dn (optimised %+.1f %%, "
            "%.2f %%), topple error %.2f deg\n",
            shape->kind.c_str(), n, 100 * q.volume_error, 100 * q.surface_rms, 100 * opt.volume_error,
            100 * opt.surface_rms, q.topple_error_deg);
    }
    EXPECT_EQ(parse_method("inscribed"), ClumpMethod::inscribed);
    EXPECT_EQ(method_name(ClumpMethod::inscribed), "inscribed");
}

// The inscribed clump moves a shallow sphere towards the centroid; where the
// centroid lies outside the shape (a U, its arms 0.1 m thick and 1 m tall on a
// 0.1 m base: the centroid sits 0.37 m up in the gap between the arms) no
// move helps, and the builder says so instead of writing a negative radius.
TEST(ClumpBuilders, AnInscribedSphereThatCannotBeMovedInsideFailsLoudly) {
    // The U's outline in x-z, counter-clockwise, as three convex pieces.
    const std::vector<Eigen::Vector2d> outline = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.9, 1.0},
                                                  {0.9, 0.1}, {0.1, 0.1}, {0.1, 1.0}, {0.0, 1.0}};
    const std::vector<std::array<int, 3>> cap = {{0, 1, 4}, {0, 4, 5}, {1, 2, 3},
                                                 {1, 3, 4}, {0, 5, 6}, {0, 6, 7}};
    TriangleMesh u; // extruded 1 m along y
    for (const double y : {0.0, 1.0})
        for (const Eigen::Vector2d &p : outline)
            u.vertices.emplace_back(p.x(), y, p.y());
    const int n = static_cast<int>(outline.size());
    for (const auto &t : cap) {
        u.triangles.push_back({t[0], t[1], t[2]});             // y = 0: ccw in x-z faces -y
        u.triangles.push_back({n + t[0], n + t[2], n + t[1]}); // y = 1, turned to face +y
    }
    for (int k = 0; k < n; ++k) {
        const int a = k, b = (k + 1) % n;
        u.triangles.push_back({a, n + a, n + b});
        u.triangles.push_back({a, n + b, b});
    }
    const std::string path = testing::TempDir() + "u_shape.stl";
    write_stl(u, path);
    const Shape shape = make_stl_shape(path, 2400.0);
    std::remove(path.c_str());
    ASSERT_NEAR(shape.props.volume, 0.28, 1e-6); // outward faces: positive (STL stores floats)
    const ShapeQuery query(shape.mesh);
    ASSERT_GT(query.signed_distance(Eigen::Vector3d::Zero()), 0.0); // the centroid (origin) is outside
    Clump clump = {{Eigen::Vector3d(0.0, 0.0, 0.05), 0.05}};        // in the gap, above the centroid
    try {
        detail::hold_inside(clump, shape, query);
        FAIL() << "a sphere outside the U was kept, radius " << clump[0].radius;
    } catch (const InputError &e) {
        EXPECT_NE(std::string(e.what()).find("--method inscribed: a sphere cannot be moved inside the shape "
                                             "towards its centroid, which lies outside it"),
                  std::string::npos)
            << e.what();
    }
}

TEST(ClumpBuilders, ErrorsShrinkAsSpheresGrow) {
    for (const Shape *shape : {&unit_cube(), &dolos()}) {
        double previous_rms = HUGE_VAL, previous_greedy_volume = HUGE_VAL;
        for (int n : {8, 25, 80}) {
            const ClumpQuality opt = evaluate_clump(*shape, build_clump(*shape, ClumpMethod::optimised, n));
            const ClumpQuality greedy = evaluate_clump(*shape, build_clump(*shape, ClumpMethod::greedy, n));
            EXPECT_LT(opt.surface_rms, previous_rms) << shape->kind << " N=" << n;
            EXPECT_LT(std::abs(greedy.volume_error), previous_greedy_volume) << shape->kind << " N=" << n;
            previous_rms = opt.surface_rms;
            previous_greedy_volume = std::abs(greedy.volume_error);
        }
    }
}

TEST(ClumpBuilders, OptimisedMatchesVolumeAndBeatsBaseline) {
    for (const Shape *shape : {&unit_cube(), &dolos()})
        for (int n : {10, 40}) {
            const Clump clump = build_clump(*shape, ClumpMethod::optimised, n);
            const ClumpQuality opt = evaluate_clump(*shape, clump);
            const ClumpQuality greedy = evaluate_clump(*shape, build_clump(*shape, ClumpMethod::greedy, n));
            EXPECT_LT(std::abs(opt.volume_error), 1e-3) << shape->kind << " N=" << n;
            EXPECT_LT(opt.surface_rms, greedy.surface_rms) << shape->kind << " N=" << n;
            EXPECT_LT(opt.inertia_error, greedy.inertia_error) << shape->kind << " N=" << n;
            // Documented floor on the body's radii; the corner spheres
            // (clump_support.h) are exactly kSupportRadius Dn.
            for (const Sphere &s : clump) {
                const bool corner = std::abs(s.radius - kSupportRadius * shape->Dn()) <= 1e-12 * shape->Dn();
                EXPECT_TRUE(corner || s.radius >= 0.03 * shape->Dn() * (1 - 1e-9)) << s.radius;
            }
        }
}

TEST(ClumpTolerance, FewestSpheresMeetsAllTolerances) {
    const double tol_volume = 0.01, tol_surface = 0.03, tol_topple = 1.0;
    const ToleranceSearch s =
        fewest_spheres(unit_cube(), ClumpMethod::optimised, {tol_volume, tol_surface, tol_topple}, 200);
    ASSERT_TRUE(s.met);
    EXPECT_LE(std::abs(s.quality.volume_error), tol_volume);
    EXPECT_LE(s.quality.surface_rms, tol_surface);
    EXPECT_LE(s.quality.topple_error_deg, tol_topple);
    EXPECT_EQ(static_cast<int>(s.clump.size()), s.quality.spheres);
    // One sphere fewer was tried and failed: the search brackets the answer.
    bool fewer_failed = false;
    for (const auto &q : s.tried)
        if (q.spheres == s.quality.spheres - 1)
            fewer_failed = q.surface_rms > tol_surface || std::abs(q.volume_error) > tol_volume ||
                           q.topple_error_deg > tol_topple;
    EXPECT_TRUE(fewer_failed);
}

TEST(ClumpTolerance, DefaultDolosMeetsAllThree) {
    const ClumpTolerances defaults;
    const ToleranceSearch s = fewest_spheres(dolos(), ClumpMethod::optimised, defaults, 200);
    ASSERT_TRUE(s.met);
    EXPECT_TRUE(meets(s.quality, defaults));
    EXPECT_GE(s.quality.spheres, 42); // one sphere per corner (40) and a body
}

TEST(ClumpTolerance, ReportsWhenItCannotBeMet) {
    const ToleranceSearch s = fewest_spheres(unit_cube(), ClumpMethod::optimised, {0.01, 0.001}, 12);
    EXPECT_FALSE(s.met);
    EXPECT_LE(s.quality.spheres, 12);
    EXPECT_THROW(fewest_spheres(unit_cube(), ClumpMethod::optimised, {0.0, 0.02}, 10), InputError);
    EXPECT_THROW(fewest_spheres(unit_cube(), ClumpMethod::optimised, {0.01, -1.0}, 10), InputError);
    EXPECT_THROW(fewest_spheres(unit_cube(), ClumpMethod::optimised, {0.01, 0.02, 0.0}, 10), InputError);
}

// One range for each tolerance, the one `armour clump` and `armour demo`
// state: fractions in (0, 1), the topple error in (0, 90) degrees.
TEST(ClumpTolerance, OneRangeForEachTolerance) {
    EXPECT_NO_THROW(check_tolerances({0.999, 0.999, 89.9}));
    const double inf = std::numeric_limits<double>::infinity();
    for (const ClumpTolerances &t :
         {ClumpTolerances{1.0, 0.02, 1.0}, ClumpTolerances{0.01, 1.0, 1.0}, ClumpTolerances{0.01, 0.02, 90.0},
          ClumpTolerances{0.01, 0.02, inf}, ClumpTolerances{0.01, 0.02, std::nan("")}})
        EXPECT_THROW(check_tolerances(t), InputError)
            << t.volume << " " << t.surface_rms << " " << t.topple_deg;
    // The search applies the same rule: a topple tolerance of 90 degrees is refused before any clump.
    EXPECT_THROW(fewest_spheres(unit_cube(), ClumpMethod::optimised, {0.01, 0.02, 90.0}, 10), InputError);
}

TEST(ClumpFiles, SphereFileRoundTripsAndSnippetCarriesExactMass) {
    const Clump clump = build_clump(unit_cube(), ClumpMethod::optimised, 6);
    const auto dir =
        std::filesystem::temp_directory_path() / ("armour_test_clump_files_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "clump.spheres").string();
    write_sphere_file(clump, path, "test");
    std::ifstream in(path);
    std::vector<Sphere> read;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream fields(line);
        Sphere s{};
        fields >> s.center.x() >> s.center.y() >> s.center.z() >> s.radius;
        read.push_back(s);
    }
    ASSERT_EQ(read.size(), clump.size());
    for (std::size_t i = 0; i < clump.size(); ++i) {
        EXPECT_EQ(read[i].center, clump[i].center);
        EXPECT_EQ(read[i].radius, clump[i].radius);
    }
    const std::string snippet = liggghts_template_snippet(unit_cube(), clump, path);
    EXPECT_NE(snippet.find("nspheres 6 "), std::string::npos);
    EXPECT_NE(snippet.find("mass 1000 use_density"), std::string::npos);
    // I = m a^2 / 6 with exactly zero products, so LIGGGHTS keeps the unit frame.
    EXPECT_NE(snippet.find("inertia_tensor 166.666666667 0 0 166.666666667 0 166.666666667"),
              std::string::npos)
        << snippet;
    std::filesystem::remove_all(dir);
}

TEST(ClumpFiles, SurfaceMeshIsOutwardAndCloseToTheSpheres) {
    const Clump one = {{Eigen::Vector3d(1, 0, 0), 0.5}};
    const TriangleMesh mesh = clump_surface_mesh(one, 3);
    const double v = signed_volume(mesh);
    EXPECT_GT(v, 0.0);
    EXPECT_NEAR(v, sphere_volume(0.5), 0.02 * sphere_volume(0.5));
}
