// Geometry foundations: exact mass properties, STL input/output, mesh
// validation and the exact cube and dolos shapes.
#include "distance_grid.h"
#include "mass_properties.h"
#include "mesh.h"
#include "mesh_check.h"
#include "shape_query.h"
#include "shapes.h"
#include "stl_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

namespace armour {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- helpers

// Axis-aligned box built by hand (no CGAL), faces outward.
TriangleMesh box_mesh(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    // Vertex i has bit 0 = x, bit 1 = y, bit 2 = z.
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},  // z = lo, z = hi
                   {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},  // y = lo, y = hi
                   {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}}; // x = lo, x = hi
    return m;
}

// Concatenation that merges vertices with identical coordinates, so that two
// solids touching at an edge or a corner share it topologically.
TriangleMesh merged(const std::vector<TriangleMesh> &parts) {
    TriangleMesh out;
    std::map<std::array<double, 3>, int> index;
    for (const auto &part : parts)
        for (const auto &t : part.triangles) {
            std::array<int, 3> tri{};
            for (int k = 0; k < 3; ++k) {
                const auto &p = part.vertices[t[k]];
                auto [it, inserted] =
                    index.try_emplace({p.x(), p.y(), p.z()}, static_cast<int>(out.vertices.size()));
                if (inserted)
                    out.vertices.push_back(p);
                tri[k] = it->second;
            }
            out.triangles.push_back(tri);
        }
    return out;
}

TriangleMesh reversed(TriangleMesh m) {
    for (auto &t : m.triangles)
        std::swap(t[1], t[2]);
    return m;
}

void bounding_box(const TriangleMesh &m, Eigen::Vector3d &lo, Eigen::Vector3d &hi) {
    lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (const auto &v : m.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
}

// Runs `fn`, expects InputError whose single-line message contains `needle`.
void expect_input_error(const std::function<void()> &fn, const std::string &needle) {
    try {
        fn();
        ADD_FAILURE() << "no InputError; expected one containing \"" << needle << "\"";
    } catch (const InputError &e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(needle), std::string::npos) << "message: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
    }
}

// A fresh directory per test, removed afterwards.
class TempDir {
  public:
    TempDir() {
        const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() / ("armour_geo_" + std::to_string(::getpid()) + "_" +
                                             info->test_suite_name() + "_" + info->name());
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    std::string file(const std::string &name) const { return (path_ / name).string(); }

  private:
    fs::path path_;
};

void write_text(const std::string &path, const std::string &text) {
    std::ofstream(path, std::ios::binary) << text;
}

// Volume and inertia by an independent method: lines parallel to z on a
// regular x-y grid; along each line the inside intervals come from the sorted
// crossings with the triangles (ray parity), and the z integrals over them are
// exact; the x-y integral is the midpoint rule. Uses neither CGAL nor the
// divergence formula, so it checks both the mesh and mass_properties.
struct LineIntegrals {
    double volume = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero(); // unit density, about the centroid
    int odd_lines = 0;                                 // lines with an odd crossing count (skipped)
};

LineIntegrals integrate_by_lines(const TriangleMesh &m, int n) {
    Eigen::Vector3d lo, hi;
    bounding_box(m, lo, hi);
    const double dx = (hi.x() - lo.x()) / n, dy = (hi.y() - lo.y()) / n;
    // An irrational-looking shift keeps the lines off edges and vertices, whose
    // crossings would otherwise be counted twice.
    const double shift_x = 0.5 + 0.0317, shift_y = 0.5 - 0.0213;
    double s0 = 0.0;
    Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
    Eigen::Matrix3d s2 = Eigen::Matrix3d::Zero();
    LineIntegrals out;
    std::vector<int> row;
    std::vector<double> zs;
    for (int j = 0; j < n; ++j) {
        const double y = lo.y() + (j + shift_y) * dy;
        row.clear();
        for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
            const auto &tri = m.triangles[t];
            const double y0 = m.vertices[tri[0]].y(), y1 = m.vertices[tri[1]].y(),
                         y2 = m.vertices[tri[2]].y();
            if (std::min({y0, y1, y2}) <= y && y <= std::max({y0, y1, y2}))
                row.push_back(t);
        }
        for (int i = 0; i < n; ++i) {
            const double x = lo.x() + (i + shift_x) * dx;
            zs.clear();
            for (int t : row) {
                const auto &a = m.vertices[m.triangles[t][0]];
                const auto &b = m.vertices[m.triangles[t][1]];
                const auto &c = m.vertices[m.triangles[t][2]];
                // Barycentric coordinates of (x, y) in the x-y projection.
                const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
                if (det == 0.0)
                    continue; // face parallel to the line: never crossed
                const double u = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
                const double v = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
                if (u < 0.0 || v < 0.0 || u + v > 1.0)
                    continue;
                zs.push_back(a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z()));
            }
            if (zs.size() % 2 != 0) {
                ++out.odd_lines;
                continue;
            }
            std::sort(zs.begin(), zs.end());
            for (std::size_t k = 0; k < zs.size(); k += 2) {
                const double z0 = zs[k], z1 = zs[k + 1];
                const double l0 = z1 - z0;
                const double l1 = 0.5 * (z1 * z1 - z0 * z0);
                const double l2 = (z1 * z1 * z1 - z0 * z0 * z0) / 3.0;
                s0 += l0;
                s1 += Eigen::Vector3d(x * l0, y * l0, l1);
                s2(0, 0) += x * x * l0;
                s2(1, 1) += y * y * l0;
                s2(2, 2) += l2;
                s2(0, 1) += x * y * l0;
                s2(0, 2) += x * l1;
                s2(1, 2) += y * l1;
            }
        }
    }
    const double cell = dx * dy;
    out.volume = s0 * cell;
    out.centroid = s1 * cell / out.volume;
    s2(1, 0) = s2(0, 1);
    s2(2, 0) = s2(0, 2);
    s2(2, 1) = s2(1, 2);
    const Eigen::Matrix3d cov = s2 * cell - out.volume * out.centroid * out.centroid.transpose();
    out.inertia = cov.trace() * Eigen::Matrix3d::Identity() - cov;
    return out;
}

// ---------------------------------------------------------------- mass properties

TEST(MassProperties, CubeOffsetFromOriginMatchesAnalytic) {
    const double a = 2.0;
    const Eigen::Vector3d offset(10.0, -20.0, 30.0);
    for (double density : {1.0, 1000.0, 2400.0, 7850.0}) {
        const auto props = mass_properties(translated(make_cube_mesh(a), offset), density);
        const double mass = density * a * a * a;
        const double moment = mass * a * a / 6.0;
        EXPECT_NEAR(props.volume, a * a * a, 1e-12 * a * a * a);
        EXPECT_NEAR(props.mass, mass, 1e-12 * mass);
        EXPECT_DOUBLE_EQ(props.density, density);
        EXPECT_LT((props.centroid - offset).norm(), 1e-12 * offset.norm());
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                EXPECT_NEAR(props.inertia(i, j), i == j ? moment : 0.0, 1e-12 * moment) << i << "," << j;
    }
}

TEST(MassProperties, RotatedBoxPrincipalFrame) {
    // Box of edges 1, 2, 3 rotated arbitrarily: principal moments are the
    // analytic m (b^2 + c^2) / 12 in ascending order, axes are the rotated
    // box axes, orthonormal and right-handed.
    const Eigen::Vector3d edges(1.0, 2.0, 3.0);
    TriangleMesh box = box_mesh(-0.5 * edges, 0.5 * edges);
    const Eigen::Matrix3d rot = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
                                 Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitX()))
                                    .toRotationMatrix();
    for (auto &v : box.vertices)
        v = rot * v + Eigen::Vector3d(0.3, -4.0, 2.5);
    const double density = 2400.0;
    const auto props = mass_properties(box, density);
    const double mass = density * 6.0;
    const Eigen::Vector3d expected(mass * (4 + 9) / 12.0, mass * (1 + 9) / 12.0, mass * (1 + 4) / 12.0);
    // Ascending: along the longest edge (z, 3 m) the moment is smallest.
    const Eigen::Vector3d ascending(expected[2], expected[1], expected[0]);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(props.principal_moments[i], ascending[i], 1e-12 * expected.maxCoeff());
    const Eigen::Matrix3d &axes = props.principal_axes;
    EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
    EXPECT_LT((axes.transpose() * axes - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    for (int i = 0; i < 3; ++i) {
        // Principal axis i is box axis 2 - i (up to sign).
        EXPECT_NEAR(std::abs(axes.col(i).dot(rot.col(2 - i))), 1.0, 1e-12);
        EXPECT_LT((props.inertia * axes.col(i) - props.principal_moments[i] * axes.col(i)).norm(),
                  1e-12 * expected.maxCoeff());
    }
}

// ---------------------------------------------------------------- cube shapes

TEST(CubeMesh, ValidWithExactVolume) {
    const TriangleMesh cube = make_cube_mesh(1.5);
    EXPECT_EQ(cube.vertices.size(), 8u);
    EXPECT_EQ(cube.triangles.size(), 12u);
    EXPECT_NO_THROW(validate_mesh(cube, "cube"));
    EXPECT_NEAR(signed_volume(cube), 1.5 * 1.5 * 1.5, 1e-14);
}

TEST(CubeMesh, ChamferedVolumeAndSymmetry) {
    const double a = 1.0;
    for (double c : {0.01, 0.1, 0.25, 0.49}) {
        const TriangleMesh mesh = make_cube_mesh(a, c);
        EXPECT_NO_THROW(validate_mesh(mesh, "chamfered cube"));
        // 6 square faces, 12 chamfer rectangles (2 triangles each), 8 corner triangles.
        EXPECT_EQ(mesh.triangles.size(), 44u) << "c = " << c;
        EXPECT_EQ(mesh.vertices.size(), 24u);
        const double core = a - 2 * c;
        const double exact =
            core * core * core + 6 * core * core * c + 6 * core * c * c + 4.0 / 3.0 * c * c * c;
        const auto props = mass_properties(mesh, 1.0);
        EXPECT_NEAR(props.volume, exact, 1e-13) << "c = " << c;
        // Cubic symmetry: isotropic inertia, centroid at the origin.
        EXPECT_LT(props.centroid.norm(), 1e-14);
        const double moment = props.inertia(0, 0);
        EXPECT_NEAR(props.inertia(1, 1), moment, 1e-13 * moment);
        EXPECT_NEAR(props.inertia(2, 2), moment, 1e-13 * moment);
        EXPECT_NEAR(props.inertia(0, 1), 0.0, 1e-13 * moment);
        EXPECT_NEAR(props.inertia(0, 2), 0.0, 1e-13 * moment);
        EXPECT_NEAR(props.inertia(1, 2), 0.0, 1e-13 * moment);
        // Chamfering removes mass farthest from the centre: inertia below the sharp cube's.
        EXPECT_LT(moment, exact * a * a / 6.0);
    }
}

// ---------------------------------------------------------------- dolos

double max_abs_coord_error(const TriangleMesh &m, double half) {
    Eigen::Vector3d lo, hi;
    bounding_box(m, lo, hi);
    return std::max((lo + Eigen::Vector3d::Constant(half)).cwiseAbs().maxCoeff(),
                    (hi - Eigen::Vector3d::Constant(half)).cwiseAbs().maxCoeff());
}

TEST(Dolos, PartsAreValidConvexSolids) {
    const double H = 2.0;
    const auto parts = make_dolos_parts(H, 0.33);
    ASSERT_EQ(parts.size(), 3u);
    double sum = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        EXPECT_NO_THROW(validate_mesh(parts[i], "part " + std::to_string(i)));
        const double v = signed_volume(parts[i]);
        sum += v;
        largest = std::max(largest, v);
    }
    // Shank: regular octagon prism, area 2 (sqrt 2 - 1) C^2, length H - F.
    const double C = 0.33 * H, F = 1.1 * C;
    EXPECT_NEAR(signed_volume(parts[0]), 2.0 * (std::sqrt(2.0) - 1.0) * C * C * (H - F), 1e-12);
    // Fluke: two frusta of an octagonal pyramid, height H/2 each, end areas
    // A(F) and A(T) with A(d) = 2 (sqrt 2 - 1) d^2.
    const double T = 0.8 * C;
    const double a_mid = 2.0 * (std::sqrt(2.0) - 1.0) * F * F, a_tip = 2.0 * (std::sqrt(2.0) - 1.0) * T * T;
    const double fluke = 2.0 * (0.5 * H / 3.0) * (a_mid + a_tip + std::sqrt(a_mid * a_tip));
    EXPECT_NEAR(signed_volume(parts[1]), fluke, 1e-12);
    EXPECT_NEAR(signed_volume(parts[2]), fluke, 1e-12);
    // The parts overlap, so the union is less than their sum but more than any part.
    const double united = signed_volume(make_dolos_mesh(H, 0.33));
    EXPECT_LT(united, sum);
    EXPECT_GT(united, largest);
}

class DolosWaist : public ::testing::TestWithParam<double> {};

TEST_P(DolosWaist, UnionIsValidBoundedAndSymmetric) {
    const double H = 3.0, r = GetParam();
    const TriangleMesh mesh = make_dolos_mesh(H, r);
    EXPECT_NO_THROW(validate_mesh(mesh, "dolos r=" + std::to_string(r)));
    EXPECT_LT(max_abs_coord_error(mesh, 0.5 * H), 1e-12 * H);

    // x -> -x, y <-> z swaps the flukes; y -> -y and z -> -z are symmetries.
    const auto props = mass_properties(mesh, 1.0);
    const double scale = props.inertia.trace();
    EXPECT_LT(props.centroid.norm(), 1e-12 * H);
    EXPECT_NEAR(props.inertia(1, 1), props.inertia(2, 2), 1e-10 * scale);
    EXPECT_NEAR(props.inertia(0, 1), 0.0, 1e-10 * scale);
    EXPECT_NEAR(props.inertia(0, 2), 0.0, 1e-10 * scale);
    EXPECT_NEAR(props.inertia(1, 2), 0.0, 1e-10 * scale);
}

INSTANTIATE_TEST_SUITE_P(Range, DolosWaist, ::testing::Values(0.25, 0.33, 0.40, 0.50));

TEST(Dolos, MassPropertiesAgreeWithLineIntegration) {
    const double H = 2.0;
    const TriangleMesh mesh = make_dolos_mesh(H, 0.33);
    const auto exact = mass_properties(mesh, 1.0);
    const auto lines = integrate_by_lines(mesh, 500);
    EXPECT_EQ(lines.odd_lines, 0);
    EXPECT_NEAR(lines.volume, exact.volume, 0.005 * exact.volume);
    EXPECT_LT((lines.centroid - exact.centroid).norm(), 0.005 * H);
    const double scale = exact.inertia.trace() / 3.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            EXPECT_NEAR(lines.inertia(i, j), exact.inertia(i, j), 0.005 * scale) << i << "," << j;
}

TEST(Dolos, VolumeRatiosMatchDocumentation) {
    // The table in docs/dolos.md; a change of proportions must update it.
    const std::vector<std::pair<double, double>> table = {
        {0.25, 0.119404}, {0.33, 0.193579}, {0.40, 0.266026}, {0.50, 0.375166}};
    for (const auto &[r, ratio] : table)
        EXPECT_NEAR(signed_volume(make_dolos_mesh(1.0, r)), ratio, 1e-6) << "r = " << r;
}

TEST(Dolos, LineIntegrationReproducesCube) {
    // The independent integrator itself is checked on a solid with a known answer.
    const double a = 1.0;
    const auto lines =
        integrate_by_lines(translated(make_cube_mesh(a, 0.1), Eigen::Vector3d(0.2, 0.1, 0.3)), 300);
    const double core = a - 0.2, c = 0.1;
    const double exact = core * core * core + 6 * core * core * c + 6 * core * c * c + 4.0 / 3.0 * c * c * c;
    EXPECT_EQ(lines.odd_lines, 0);
    EXPECT_NEAR(lines.volume, exact, 0.005 * exact);
}

// ---------------------------------------------------------------- shapes

TEST(Shapes, CubeShapeRecord) {
    const Shape s = make_cube_shape(1.0, 0.0, 2400.0);
    EXPECT_EQ(s.kind, "cube");
    EXPECT_EQ(s.description, "cube a=1 m chamfer=0 m");
    EXPECT_NEAR(s.Dn(), 1.0, 1e-14);
    EXPECT_NEAR(s.props.mass, 2400.0, 1e-10);
    EXPECT_LT(s.props.centroid.norm(), 1e-15);
}

TEST(Shapes, DolosShapeRecordCentred) {
    const Shape s = make_dolos_shape(2.0, 0.33, 2400.0);
    EXPECT_EQ(s.kind, "dolos");
    EXPECT_EQ(s.description, "dolos H=2 m r=0.33");
    EXPECT_LT(s.props.centroid.norm(), 1e-12);
    EXPECT_NEAR(s.Dn(), std::cbrt(s.props.volume), 1e-15);
    EXPECT_NEAR(s.props.mass, 2400.0 * s.props.volume, 1e-9);
}

TEST(Shapes, StlShapeIsCentredAndKeepsAxes) {
    TempDir dir;
    const std::string path = dir.file("box.stl");
    const Eigen::Vector3d lo(5.0, 6.0, 7.0), hi(6.0, 8.0, 10.0);
    write_stl(box_mesh(lo, hi), path, true);
    const Shape s = make_stl_shape(path, 2000.0);
    EXPECT_EQ(s.kind, "stl");
    EXPECT_EQ(s.description, "stl " + path);
    EXPECT_NEAR(s.props.volume, 6.0, 1e-12);
    EXPECT_LT(s.props.centroid.norm(), 1e-12);
    Eigen::Vector3d mlo, mhi;
    bounding_box(s.mesh, mlo, mhi);
    // Translated only: the box keeps its 1 x 2 x 3 extents along x, y, z.
    EXPECT_LT((mhi - mlo - (hi - lo)).norm(), 1e-12);
    EXPECT_LT((mlo + 0.5 * (hi - lo)).norm(), 1e-12);
}

TEST(Shapes, StlShapeRejectsBadMeshNamingTheFile) {
    TempDir dir;
    const std::string path = dir.file("open.stl");
    TriangleMesh open = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
    open.triangles.pop_back();
    write_stl(open, path, false);
    expect_input_error([&] { make_stl_shape(path, 2400.0); }, path + ": mesh is not closed");
}

TEST(Shapes, BadArgumentsNameTheOption) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    expect_input_error([] { make_cube_shape(-1.0, 0.0, 2400.0); },
                       "--size: cube edge must be > 0 m (got -1)");
    expect_input_error([&] { make_cube_shape(nan, 0.0, 2400.0); }, "--size:");
    expect_input_error([&] { make_cube_shape(inf, 0.0, 2400.0); }, "--size:");
    expect_input_error([] { make_cube_shape(1.0, 0.5, 2400.0); }, "--chamfer:");
    expect_input_error([] { make_cube_shape(1.0, -0.1, 2400.0); }, "--chamfer:");
    expect_input_error([] { make_cube_shape(1.0, 0.0, 0.0); }, "--density:");
    expect_input_error([&] { make_cube_shape(1.0, 0.0, inf); }, "--density:");
    expect_input_error([] { make_dolos_shape(0.0, 0.33, 2400.0); },
                       "--height: dolos height must be > 0 m (got 0)");
    expect_input_error([] { make_dolos_shape(2.0, 0.6, 2400.0); },
                       "--waist: dolos waist ratio must be in [0.25, 0.50] (got 0.6)");
    expect_input_error([] { make_dolos_shape(2.0, 0.2, 2400.0); }, "--waist:");
    expect_input_error([&] { make_dolos_shape(2.0, nan, 2400.0); }, "--waist:");
    expect_input_error([] { make_dolos_shape(2.0, 0.33, -5.0); }, "--density:");
    expect_input_error([] { make_stl_shape("/nonexistent/unit.stl", -1.0); }, "--density:");
}

// ---------------------------------------------------------------- STL

TEST(Stl, AsciiRoundTripIsExact) {
    TempDir dir;
    const std::string path = dir.file("dolos_ascii.stl");
    const TriangleMesh mesh = make_dolos_mesh(2.0, 0.33);
    write_stl(mesh, path, false, "dolos");
    EXPECT_FALSE(fs::exists(path + ".tmp"));
    const TriangleMesh back = read_stl(path);
    ASSERT_EQ(back.triangles.size(), mesh.triangles.size());
    EXPECT_EQ(back.vertices.size(), mesh.vertices.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
            ASSERT_EQ(back.vertices[back.triangles[t][k]], mesh.vertices[mesh.triangles[t][k]]);
    EXPECT_EQ(signed_volume(back), signed_volume(mesh));
}

TEST(Stl, BinaryRoundTripWithinFloatPrecision) {
    TempDir dir;
    const std::string path = dir.file("dolos_binary.stl");
    const TriangleMesh mesh = make_dolos_mesh(2.0, 0.33);
    write_stl(mesh, path, true);
    EXPECT_EQ(fs::file_size(path), 84 + 50 * mesh.triangles.size());
    const TriangleMesh back = read_stl(path);
    EXPECT_EQ(back.triangles.size(), mesh.triangles.size());
    EXPECT_EQ(back.vertices.size(), mesh.vertices.size());
    // float32 coordinates: relative error ~6e-8 per coordinate.
    EXPECT_NEAR(signed_volume(back), signed_volume(mesh), 1e-6 * signed_volume(mesh));
}

TEST(Stl, MergesVerticesAndDropsRepeatedVertexTriangles) {
    TempDir dir;
    const std::string path = dir.file("sliver.stl");
    TriangleMesh cube = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
    cube.triangles.push_back({0, 0, 1}); // no area: dropped by the reader
    write_stl(cube, path, false);
    const TriangleMesh back = read_stl(path);
    EXPECT_EQ(back.vertices.size(), 8u);
    EXPECT_EQ(back.triangles.size(), 12u);
    EXPECT_NO_THROW(validate_mesh(back, path));
}

TEST(Stl, BinaryHeaderStartingWithSolidIsStillBinary) {
    // Many exporters write "solid" into a binary header; the size decides.
    TempDir dir;
    const std::string path = dir.file("solid_header.stl");
    write_stl(make_cube_mesh(1.0), path, true);
    {
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.write("solid cube", 10);
    }
    EXPECT_EQ(read_stl(path).triangles.size(), 12u);
    fs::resize_file(path, 84 + 50 * 11);
    expect_input_error([&] { read_stl(path); }, path + ": truncated binary STL");
}

TEST(Stl, ReadErrorsNameFileAndReason) {
    TempDir dir;
    expect_input_error([] { read_stl("/nonexistent/dir/unit.stl"); },
                       "/nonexistent/dir/unit.stl: cannot open");

    const std::string empty = dir.file("empty.stl");
    write_text(empty, "");
    expect_input_error([&] { read_stl(empty); }, empty + ": file is empty");

    const std::string truncated = dir.file("truncated.stl");
    write_stl(make_cube_mesh(1.0), truncated, true);
    fs::resize_file(truncated, 84 + 50 * 12 - 7);
    expect_input_error([&] { read_stl(truncated); }, truncated + ": truncated binary STL");

    const std::string tiny = dir.file("tiny.stl");
    write_text(tiny, "abc");
    expect_input_error([&] { read_stl(tiny); }, tiny + ": truncated binary STL");

    const std::string bad_number = dir.file("bad_number.stl");
    write_text(bad_number,
               "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 zero\n");
    expect_input_error([&] { read_stl(bad_number); }, bad_number + ": malformed ASCII STL at line 5");

    const std::string four = dir.file("four_vertices.stl");
    write_text(four, "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                     "vertex 1 1 0\nendloop\nendfacet\nendsolid x\n");
    expect_input_error([&] { read_stl(four); }, four + ": malformed ASCII STL at line 7");

    const std::string unfinished = dir.file("unfinished.stl");
    write_text(unfinished, "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
    expect_input_error([&] { read_stl(unfinished); }, unfinished + ": malformed ASCII STL at line 4");

    const std::string none = dir.file("none.stl");
    write_text(none, "solid x\nendsolid x\n");
    expect_input_error([&] { read_stl(none); }, none + ": no triangles");
}

// ---------------------------------------------------------------- mesh validation

const Eigen::Vector3d kZero = Eigen::Vector3d::Zero();
const Eigen::Vector3d kOne = Eigen::Vector3d::Ones();

TEST(MeshCheck, RejectsMissingOrBadTriangles) {
    expect_input_error([] { validate_mesh(TriangleMesh{}, "empty"); }, "empty: mesh has no triangles");
    TriangleMesh bad = box_mesh(kZero, kOne);
    bad.triangles[3][1] = 99;
    expect_input_error([&] { validate_mesh(bad, "bad"); },
                       "bad: triangle 3 has vertex index 99 outside [0, 8)");
}

TEST(MeshCheck, RejectsDegenerateTriangle) {
    TriangleMesh m = box_mesh(kZero, kOne);
    m.vertices.emplace_back(0.5, 0.0, 0.0); // on the edge from vertex 0 to vertex 1
    m.triangles.push_back({0, 8, 1});
    expect_input_error([&] { validate_mesh(m, "m"); },
                       "m: 1 degenerate (zero-area) triangle, e.g. triangle 12");
}

TEST(MeshCheck, RejectsOpenMesh) {
    TriangleMesh m = make_cube_mesh(1.0);
    m.triangles.erase(m.triangles.begin() + 4);
    expect_input_error([&] { validate_mesh(m, "open.stl"); }, "open.stl: mesh is not closed");
    expect_input_error([&] { validate_mesh(m, "open.stl"); }, ": 3 edges");
}

TEST(MeshCheck, RejectsNonManifoldEdge) {
    // Two boxes sharing only the edge x = y = 1.
    const TriangleMesh m = merged({box_mesh(kZero, kOne), box_mesh({1, 1, 0}, {2, 2, 1})});
    expect_input_error([&] { validate_mesh(m, "m"); }, "m: mesh is not edge-manifold");
    expect_input_error([&] { validate_mesh(m, "m"); }, ": 1 edge, e.g. edge from vertex");
}

TEST(MeshCheck, RejectsNonManifoldVertex) {
    // Two boxes sharing only the corner (1, 1, 1).
    const TriangleMesh m = merged({box_mesh(kZero, kOne), box_mesh(kOne, 2 * kOne)});
    expect_input_error([&] { validate_mesh(m, "m"); }, "m: mesh is not vertex-manifold");
}

TEST(MeshCheck, RejectsInwardFaces) {
    const TriangleMesh m = reversed(make_cube_mesh(2.0));
    expect_input_error([&] { validate_mesh(m, "m"); }, "m: faces point inward (signed volume -8 m^3)");
}

TEST(MeshCheck, RejectsInconsistentOrientation) {
    TriangleMesh m = make_cube_mesh(1.0);
    std::swap(m.triangles[5][0], m.triangles[5][1]);
    expect_input_error([&] { validate_mesh(m, "m"); }, "m: inconsistent orientation");
}

TEST(MeshCheck, RejectsSelfIntersection) {
    const TriangleMesh m = merged({box_mesh(kZero, kOne), box_mesh(0.5 * kOne, 1.5 * kOne)});
    expect_input_error([&] { validate_mesh(m, "m"); }, "m: mesh intersects itself");
}

TEST(MeshCheck, DisjointSolidsAreAccepted) {
    const TriangleMesh m = merged({box_mesh(kZero, kOne), box_mesh(2 * kOne, 3 * kOne)});
    EXPECT_NO_THROW(validate_mesh(m, "m"));
}

TEST(MeshCheck, RejectsZeroVolume) {
    // A tetrahedron 1e-14 m high on a 1 m base: valid topology, no face
    // intersects another, but the volume is rounding noise.
    TriangleMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 1e-14}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    expect_input_error([&] { validate_mesh(m, "flat"); }, "flat: zero volume");
    // An exactly flat closed surface has coplanar overlapping faces, so it is
    // already caught, exactly, as a self-intersection.
    TriangleMesh pillow;
    pillow.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    pillow.triangles = {{0, 1, 2}, {0, 2, 1}};
    expect_input_error([&] { validate_mesh(pillow, "pillow"); }, "pillow: mesh intersects itself");
    // The same tetrahedron 1 m high is a valid solid.
    m.vertices[3].z() = 1.0;
    EXPECT_NO_THROW(validate_mesh(m, "tet"));
}

TEST(Shapes, ConvexPartsAreInTheUnitFrame) {
    // The parts of a dolos move with its union: together they span exactly the
    // union's bounding box, and the cube's one part is the cube itself.
    const Shape dolos = make_dolos_shape(2.0, 0.33, 2400.0);
    ASSERT_EQ(dolos.convex_parts.size(), 3u);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo, mlo = lo, mhi = -lo;
    for (const auto &part : dolos.convex_parts)
        for (const auto &v : part.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
    for (const auto &v : dolos.mesh.vertices) {
        mlo = mlo.cwiseMin(v);
        mhi = mhi.cwiseMax(v);
    }
    EXPECT_LT((lo - mlo).norm() + (hi - mhi).norm(), 1e-12);
    const Shape cube = make_cube_shape(1.0, 0.0, 2400.0);
    ASSERT_EQ(cube.convex_parts.size(), 1u);
    EXPECT_NEAR(signed_volume(cube.convex_parts[0]), 1.0, 1e-12);
}

TEST(Mesh, ClosestPointOnTriangleCoversEveryRegion) {
    const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    auto nearest = [&](const Eigen::Vector3d &p, const Eigen::Vector3d &expected) {
        EXPECT_LT((closest_point_on_triangle(p, a, b, c) - expected).norm(), 1e-15) << p.transpose();
    };
    nearest({0.2, 0.2, 5}, {0.2, 0.2, 0}); // face
    nearest({-1, -1, 0}, a);               // vertices
    nearest({2, -1, 0}, b);
    nearest({-1, 3, 1}, c);
    nearest({0.5, -2, 0}, {0.5, 0, 0}); // edges
    nearest({-2, 0.5, 0}, {0, 0.5, 0});
    nearest({1, 1, 0}, {0.5, 0.5, 0});
}

TEST(DistanceGrid, SameDistancesAsTheAabbTree) {
    // The grid only prunes triangles that cannot be nearest: every covered
    // point must get the AABB tree's exact distance (to rounding).
    const Shape dolos = make_dolos_shape(1.0, kDolosWaistDefault, 2400.0);
    const ShapeQuery tree(dolos.mesh);
    const DistanceGrid grid(dolos.mesh, 0.3, 12);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.9, 0.9);
    int covered = 0;
    for (int i = 0; i < 20000; ++i) {
        const Eigen::Vector3d p(u(rng), u(rng), u(rng));
        if (!grid.covers(p))
            continue;
        ++covered;
        ASSERT_NEAR(grid.distance(p), tree.distance(p), 1e-12) << "at " << p.transpose();
    }
    EXPECT_GT(covered, 10000);
    // Pruning must actually prune, or the grid is a slow brute force.
    EXPECT_LT(grid.mean_candidates(), 0.25 * static_cast<double>(dolos.mesh.triangles.size()));
}

TEST(BoxDistance, ClosedFormMatchesTheTriangleQuery) {
    // The mask's closed form for boxes must give the AABB tree's exact
    // signed distance (to rounding) inside, outside, near faces, edges and
    // corners.
    TriangleMesh box = make_cube_mesh(1.0);
    for (Eigen::Vector3d &v : box.vertices)
        v = v.cwiseProduct(Eigen::Vector3d(0.3, 0.2, 0.5)); // a 0.3 x 0.2 x 0.5 m box
    const auto half = axis_aligned_box_half_extents(box);
    ASSERT_TRUE(half.has_value());
    EXPECT_NEAR((*half - Eigen::Vector3d(0.15, 0.1, 0.25)).norm(), 0.0, 1e-15);
    const ShapeQuery tree(box);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    int inside = 0;
    for (int i = 0; i < 20000; ++i) {
        const Eigen::Vector3d p(u(rng), u(rng), u(rng));
        const double d = box_signed_distance(p, *half);
        inside += d < 0.0;
        ASSERT_NEAR(d, tree.signed_distance(p), 1e-12) << "at " << p.transpose();
    }
    EXPECT_GT(inside, 500);
}

TEST(BoxDistance, OnlyAxisAlignedCentredBoxesAreRecognised) {
    EXPECT_TRUE(axis_aligned_box_half_extents(make_cube_mesh(0.1)).has_value());
    EXPECT_FALSE(axis_aligned_box_half_extents(make_cube_mesh(0.1, 0.01)).has_value()); // chamfered
    EXPECT_FALSE(
        axis_aligned_box_half_extents(translated(make_cube_mesh(0.1), {0.01, 0.0, 0.0})).has_value());
    TriangleMesh turned = make_cube_mesh(0.1);
    const Eigen::Matrix3d r = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (Eigen::Vector3d &v : turned.vertices)
        v = r * v;
    EXPECT_FALSE(axis_aligned_box_half_extents(turned).has_value());
    // Corners only, but two faces missing: not the box.
    TriangleMesh open = make_cube_mesh(0.1);
    open.triangles.resize(open.triangles.size() - 4);
    EXPECT_FALSE(axis_aligned_box_half_extents(open).has_value());
    EXPECT_FALSE(axis_aligned_box_half_extents(make_dolos_mesh(1.0, kDolosWaistDefault)).has_value());
}

TEST(PartBelowPlane, CubeCutsMatchTheirClosedForms) {
    const TriangleMesh cube = make_cube_mesh(1.0);
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    // A slab: the cube below z = 0.2 is 1 x 1 x 0.7, centred at z = -0.15.
    PartBelowPlane slab = part_below_plane(cube, {0.0, 0.0, 0.2}, up);
    EXPECT_NEAR(slab.volume, 0.7, 1e-12);
    EXPECT_NEAR((slab.centroid - Eigen::Vector3d(0.0, 0.0, -0.15)).norm(), 0.0, 1e-12);
    // Turned 45 degrees about x and cut through its centre: the lower half is
    // a prism whose section is a right isosceles triangle of height sqrt(2)/2,
    // its centroid a third of that below the cut.
    TriangleMesh turned = cube;
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(0.25 * std::acos(-1.0), Eigen::Vector3d::UnitX()).toRotationMatrix();
    for (Eigen::Vector3d &v : turned.vertices)
        v = r * v;
    const PartBelowPlane prism = part_below_plane(turned, Eigen::Vector3d::Zero(), up);
    EXPECT_NEAR(prism.volume, 0.5, 1e-12);
    EXPECT_NEAR((prism.centroid - Eigen::Vector3d(0.0, 0.0, -std::sqrt(2.0) / 6.0)).norm(), 0.0, 1e-12);
    // Wholly below and wholly above.
    EXPECT_NEAR(part_below_plane(cube, {0.0, 0.0, 0.5}, up).volume, 1.0, 1e-12);
    const PartBelowPlane dry = part_below_plane(cube, {0.0, 0.0, -0.5}, up);
    EXPECT_EQ(dry.volume, 0.0);
    EXPECT_EQ(dry.centroid, Eigen::Vector3d(0.0, 0.0, -0.5));
}

TEST(PartBelowPlane, TheTwoSidesOfAnyCutAddUpToTheDolos) {
    // Volume and first moment are additive: the parts below a plane and
    // below its reverse make the whole dolos, whatever the plane.
    const TriangleMesh dolos = make_dolos_mesh(1.0, kDolosWaistDefault);
    const MassProperties whole = mass_properties(dolos, 1.0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    for (int i = 0; i < 50; ++i) {
        const Eigen::Vector3d point(u(rng), u(rng), u(rng));
        const Eigen::Vector3d n = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
        const PartBelowPlane below = part_below_plane(dolos, point, n);
        const PartBelowPlane above = part_below_plane(dolos, point, -n);
        EXPECT_GE(below.volume, 0.0);
        EXPECT_GE(above.volume, 0.0);
        ASSERT_NEAR(below.volume + above.volume, whole.volume, 1e-12 * whole.volume);
        const Eigen::Vector3d moment = below.volume * below.centroid + above.volume * above.centroid;
        ASSERT_NEAR((moment / whole.volume - whole.centroid).norm(), 0.0, 1e-12);
    }
}

TEST(ClippedToBox, KeepsExactlyThePartInside) {
    // A 10 m block whose top face is z = 0, clipped to a 2.4 x 0.18 m flume
    // box reaching 1 cm below it: only the top face is inside, area 2.4 x
    // 0.18, every triangle inside the box and still facing +z. A box above
    // the block keeps nothing.
    const TriangleMesh block = translated(make_cube_mesh(10.0), Eigen::Vector3d(0.0, 0.0, -5.0));
    const Eigen::Vector3d lo(0.0, -0.09, -0.01), hi(2.4, 0.09, 0.42);
    const TriangleMesh floor = clipped_to_box(block, lo, hi);
    double area = 0.0;
    for (const auto &t : floor.triangles) {
        const Eigen::Vector3d &a = floor.vertices[t[0]];
        const Eigen::Vector3d n = (floor.vertices[t[1]] - a).cross(floor.vertices[t[2]] - a);
        area += 0.5 * n.norm();
        EXPECT_GT(n.normalized().z(), 1.0 - 1e-12);
        for (int c = 0; c < 3; ++c) {
            const Eigen::Vector3d &v = floor.vertices[t[c]];
            EXPECT_TRUE(((v - lo).array() >= -1e-12).all() && ((hi - v).array() >= -1e-12).all())
                << v.transpose();
        }
    }
    EXPECT_NEAR(area, 2.4 * 0.18, 1e-12);
    EXPECT_TRUE(clipped_to_box(block, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 1, 2)).triangles.empty());
    // A closed cube wholly inside keeps its surface area.
    const TriangleMesh cube = translated(make_cube_mesh(0.1), Eigen::Vector3d(1.2, 0.0, 0.2));
    EXPECT_NEAR(surface_area(clipped_to_box(cube, lo, hi)), surface_area(cube), 1e-15);
}

} // namespace
} // namespace armour
