// The fluid-structure coupler core: mask, loads, added-mass-corrected advance.
//
// Added mass, and why the corrected scheme is the stable partitioned one
//     A body accelerating in a fluid pushes fluid along: the fluid load holds
//     a reaction -m_a a proportional to the body's OWN acceleration (m_a =
//     C_a rho_f V; C_a = 0.5 for a sphere in potential flow). A partitioned
//     scheme measures the fluid load from the fluid step solved with the body
//     motion of the previous step, so the measured load carries the reaction
//     to the previous acceleration:
//         F_measured,n = F_rest - m_a a_{n-1}     (F_rest: buoyancy, drag, ...)
//     Plain explicit coupling applies it as it is:
//         m a_n = F_rest + m g - m_a a_{n-1}
//     a linear recurrence with amplification -m_a / m: the acceleration
//     oscillates with a sign flip every step and grows when m_a > m, i.e. when
//     rho_s / rho_f < C_a. Light units (or a large added mass) blow up, however
//     small the time step. The correction moves the added-mass reaction to
//     the implicit side with an ESTIMATED m_a (the coefficient in settings):
//     add back m_a a_{n-1} to what was measured, then divide by m + m_a:
//         (m + m_a) a_n = F_measured,n + m_a a_{n-1} + m g
//     With the true added mass m_a,t in the measured load this reads
//         (m + m_a) a_n = F_rest + m g + (m_a - m_a,t) a_{n-1}
//     amplification (m_a - m_a,t) / (m + m_a): exact (zero) when the estimate
//     is right, and stable whenever m_a,t < m + 2 m_a, i.e. an estimate of
//     even half the true added mass stabilises any density ratio. In a steady
//     state (a_n = a_{n-1}) it reduces to m a = F_measured + m g: the
//     correction changes transients only, never the converged answer.
//     The engine applies gravity itself (m a = F_applied + m g), so
//         F_applied = (m (F_measured + m_a a_{n-1}) - m_a m g) / (m + m_a).
//     Rotation uses the same recurrence with an added inertia that is the
//     unit's own inertia scaled by m_a / m, I_a = C_a rho_f V I / m (one ratio
//     for all axes; the true rotational added inertia is shape-dependent and
//     anisotropic, zero for a sphere): T_applied = (m T + m_a I_w alpha_{n-1})
//     / (m + m_a) with I_w the world inertia. It is a stabiliser, not a model:
//     for a steady spin it changes nothing, in a transient it lags.
#include "coupler.h"

#include "distance_grid.h"
#include "mesh.h"
#include "shape_query.h"
#include "solid_fraction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

namespace armour {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Chords of a clump's spheres are taken along lines this many per radius of
// its smallest sphere apart (the error it leaves: tests/test_solid_fraction.cpp).
constexpr double kSphereLinesPerRadius = 16.0;

// Exact fractions are recomputed for a unit once it has moved (at its
// farthest point) by more than this fraction of the smallest cell since they
// were last computed; in between it keeps those of that pose. Their sum
// chi V is the unit's volume at any pose, so buoyancy stays exact: the solid
// only lags the unit by at most 1e-3 h (0.04 mm on 4 cm cells; the explicit
// exchange already lags it by a fluid step), and a unit at rest, or creeping
// on soft contacts, costs nothing most steps.
constexpr double kRestTolerance = 1e-3;

// A symmetric ramp (chi(d) + chi(-d) = 1) integrates a flat face exactly, so
// the mask volume differs from the unit volume only through curvature and
// edges, O(w^2). The cosine is C1 (smooth forces when a face crosses a cell)
// and has a smaller edge excess than the linear ramp: per unit length of a
// convex 90-degree edge, (2 + pi/2)(1/16 - 1/(2 pi^2)) w^2 = 0.042 w^2
// against (4 + pi)/96 w^2 = 0.074 w^2.
double ramp(double d, double w) {
    if (d <= -0.5 * w)
        return d < 0.0 || w > 0.0 ? 1.0 : 0.5;
    if (d >= 0.5 * w)
        return 0.0;
    return 0.5 - 0.5 * std::sin(kPi * d / w);
}

// The farthest point of cell i from its centre (m).
double cell_circumradius(const CellSet &cells, std::size_t i) {
    if (cells.cell_faces.empty())
        return 0.5 * std::sqrt(3.0) * std::cbrt(cells.volumes[i]);
    double r2 = 0.0;
    for (int f : cells.cell_faces[i])
        for (int p : cells.faces[f < 0 ? ~f : f])
            r2 = std::max(r2, (cells.points[p] - cells.centres[i]).squaredNorm());
    return std::sqrt(r2);
}

// Half extents (m) of cell i when it is a box along the world axes centred
// on its centre (every blockMesh hex of an unsheared block), else (-1, -1, -1).
Eigen::Vector3d cell_box_half(const CellSet &cells, std::size_t i) {
    if (cells.cell_faces.empty())
        return Eigen::Vector3d::Constant(0.5 * std::cbrt(cells.volumes[i]));
    const Eigen::Vector3d no = Eigen::Vector3d::Constant(-1.0);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
    std::vector<int> ids;
    for (int f : cells.cell_faces[i])
        for (int p : cells.faces[f < 0 ? ~f : f]) {
            if (std::find(ids.begin(), ids.end(), p) == ids.end())
                ids.push_back(p);
            lo = lo.cwiseMin(cells.points[p]);
            hi = hi.cwiseMax(cells.points[p]);
        }
    const double tolerance = 1e-9 * (hi - lo).norm();
    if (ids.size() != 8 || ((lo + hi) / 2 - cells.centres[i]).norm() > tolerance)
        return no;
    for (int p : ids)
        for (int a = 0; a < 3; ++a)
            if (std::abs(cells.points[p][a] - lo[a]) > tolerance &&
                std::abs(cells.points[p][a] - hi[a]) > tolerance)
                return no;
    return (hi - lo) / 2;
}

// Cell i (its box half extents `half` when it is one) in the frame of a unit
// at `position` turned by `to_unit`.
void cell_in_unit_frame(const CellSet &cells, std::size_t i, const Eigen::Vector3d &half,
                        const Eigen::Vector3d &position, const Eigen::Matrix3d &to_unit,
                        ConvexPolyhedron &out, std::vector<int> &ids) {
    out.clear();
    if (half.x() >= 0.0) {
        const Eigen::Vector3d lo = cells.centres[i] - half, hi = cells.centres[i] + half;
        for (int c = 0; c < 8; ++c)
            out.add_point(to_unit * (Eigen::Vector3d(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(),
                                                     c & 4 ? hi.z() : lo.z()) -
                                     position));
        for (const auto &loop : ConvexPolyhedron::kBoxLoops)
            out.add_face(loop, 4);
        return;
    }
    // The cell's own points (a hex: 8), each once, so that faces share them.
    ids.clear();
    std::vector<int> loop;
    for (int signed_face : cells.cell_faces[i]) {
        const std::vector<int> &face = cells.faces[signed_face < 0 ? ~signed_face : signed_face];
        loop.clear();
        for (int p : face) {
            const auto known = std::find(ids.begin(), ids.end(), p);
            if (known == ids.end()) {
                ids.push_back(p);
                out.add_point(to_unit * (cells.points[p] - position));
            }
            loop.push_back(static_cast<int>(std::find(ids.begin(), ids.end(), p) - ids.begin()));
        }
        if (signed_face < 0)
            std::reverse(loop.begin(), loop.end());
        out.add_face(loop.data(), static_cast<int>(loop.size()));
    }
}

// What update_mask needs of one unit template, built once.
struct UnitShape {
    std::optional<Eigen::Vector3d> box; // exact shape, when a box: half extents (m), closed form
    std::unique_ptr<ShapeQuery> query;  // exact shape otherwise: inside test, far distances
    std::unique_ptr<DistanceGrid> near; // exact shape otherwise: the same distances, fast near the unit
    const Clump *spheres = nullptr;     // clump spheres only
    std::unique_ptr<SolidShape> solid;  // exact solid fractions
    double outer = 0.0;                 // m, every point of the solid lies within this of the origin
    double inner = 0.0;                 // m, the ball of this radius about the origin is solid

    double signed_distance(const Eigen::Vector3d &x) const {
        if (box)
            return box_signed_distance(x, *box);
        if (query) {
            const double d = near->covers(x) ? near->distance(x) : query->distance(x);
            return query->inside(x) ? -d : d;
        }
        // Exact outside (distance to a union = least distance); inside it is
        // the depth in the deepest sphere, at most the true depth.
        double d = HUGE_VAL;
        for (const Sphere &s : *spheres)
            d = std::min(d, (x - s.center).norm() - s.radius);
        return d;
    }
};

// The fluid cells binned on a uniform grid, built once per cell set (the
// fluid mesh is static), so each body visits only the cells near it: the
// mask costs O(cells near units), not O(cells x units).
struct CellBins {
    std::vector<Eigen::Vector3d> centres; // the binned cell set, to recognise it
    std::vector<double> volumes;
    // m per cell: how far from its centre the cell can see a unit. The ramp:
    // half its width; exact fractions: the cell's circumradius.
    std::vector<double> half_width;
    double max_half_width = 0.0;
    // Exact fractions: each cell's half extents when it is a box along the
    // world axes (x < 0 otherwise), and its volume as the clipping sees it.
    std::vector<Eigen::Vector3d> box_half;
    std::vector<double> cell_volume;
    double smallest_cell = 0.0; // m, the least V^(1/3)
    Eigen::Vector3d lower = Eigen::Vector3d::Zero();
    double edge = 1.0; // m, bin edge
    std::array<int, 3> n{{1, 1, 1}};
    std::vector<int> first; // CSR: bin b holds cells [first[b], first[b + 1])
    std::vector<int> cells;

    bool matches(const CellSet &c) const { return c.centres == centres && c.volumes == volumes; }

    void build(const CellSet &c, std::optional<double> smoothing_cells, double largest_outer) {
        centres = c.centres;
        volumes = c.volumes;
        const std::size_t count = centres.size();
        half_width.resize(count);
        max_half_width = 0.0;
        lower = Eigen::Vector3d::Constant(HUGE_VAL);
        Eigen::Vector3d upper = Eigen::Vector3d::Constant(-HUGE_VAL);
        smallest_cell = HUGE_VAL;
        for (double v : volumes)
            smallest_cell = std::min(smallest_cell, std::cbrt(v));
        box_half.assign(smoothing_cells ? 0 : count, Eigen::Vector3d::Constant(-1.0));
        cell_volume.assign(smoothing_cells ? 0 : count, 0.0);
        ConvexPolyhedron cell;
        std::vector<int> ids;
        for (std::size_t i = 0; i < count; ++i) {
            half_width[i] =
                smoothing_cells ? 0.5 * *smoothing_cells * std::cbrt(volumes[i]) : cell_circumradius(c, i);
            if (!smoothing_cells) {
                box_half[i] = cell_box_half(c, i);
                cell_in_unit_frame(c, i, box_half[i], Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                   cell, ids);
                cell_volume[i] = cell.volume_and_centroid().volume;
            }
            max_half_width = std::max(max_half_width, half_width[i]);
            lower = lower.cwiseMin(centres[i]);
            upper = upper.cwiseMax(centres[i]);
        }
        if (count == 0) {
            first.assign(2, 0);
            cells.clear();
            return;
        }
        // A bin about one unit's reach wide, but never more bins than an
        // eighth of the cells (a long flume with small units).
        const Eigen::Vector3d extent = (upper - lower).cwiseMax(1e-12);
        const double sparse =
            std::cbrt(extent.prod() / std::max<double>(1.0, static_cast<double>(count) / 8.0));
        edge = std::max({largest_outer + max_half_width, sparse, 1e-9});
        for (int a = 0; a < 3; ++a)
            n[a] = std::max(1, static_cast<int>(std::floor(extent[a] / edge)) + 1);
        std::vector<int> bin_of(count);
        first.assign(static_cast<std::size_t>(n[0]) * n[1] * n[2] + 1, 0);
        for (std::size_t i = 0; i < count; ++i) {
            bin_of[i] = bin(index(centres[i], 0), index(centres[i], 1), index(centres[i], 2));
            ++first[bin_of[i] + 1];
        }
        for (std::size_t b = 1; b < first.size(); ++b)
            first[b] += first[b - 1];
        cells.resize(count);
        std::vector<int> next(first.begin(), first.end() - 1);
        for (std::size_t i = 0; i < count; ++i)
            cells[next[bin_of[i]]++] = static_cast<int>(i);
    }

    int index(const Eigen::Vector3d &x, int a) const {
        return std::clamp(static_cast<int>(std::floor((x[a] - lower[a]) / edge)), 0, n[a] - 1);
    }
    int bin(int i, int j, int k) const { return i + n[0] * (j + n[1] * k); }
};

} // namespace

struct Coupler::Impl {
    RigidBodyEngine &engine;
    std::vector<UnitTemplate> units;
    std::vector<int> body_unit;
    CouplerSettings settings;
    std::vector<UnitShape> shapes;
    std::vector<BodyState> states; // at the last update_mask: loads are taken about these centres
    CellMask mask;
    CellBins bins;
    ConvexPolyhedron cell; // exact fractions: the cell at hand, in the unit frame
    std::vector<int> cell_points;
    FractionScratch scratch;
    std::vector<Eigen::Vector3d> a_prev;     // m/s^2, each body's acceleration over the last advance
    std::vector<Eigen::Vector3d> alpha_prev; // rad/s^2
    // Per body: the last fluid force (N) and its last two step changes, and
    // how many steps in a row the change flipped and grew (see advance()).
    std::vector<Eigen::Vector3d> last_force, last_change;
    std::vector<int> swings;

    Impl(RigidBodyEngine &e, std::vector<UnitTemplate> u, std::vector<int> b, CouplerSettings s)
        : engine(e), units(std::move(u)), body_unit(std::move(b)), settings(std::move(s)) {}

    static bool exact_fraction(Impl &m, const UnitShape &shape, const CellSet &cells, std::size_t i,
                               const Eigen::Vector3d &position, const Eigen::Matrix3d &to_unit, double reach,
                               double &chi, Eigen::Vector3d &centroid);
    // Per body, the cells it reaches with their fractions and solid
    // centroids, and the pose they were computed at.
    struct BodyCells {
        std::vector<int> cell;
        std::vector<double> chi;
        std::vector<Eigen::Vector3d> centroid;
        Pose pose;
        bool valid = false;
    };
    std::vector<BodyCells> body_cells;
    MaskWork work; // of the last update_mask
    void cells_of_body(int k, const CellSet &cells, BodyCells &own);
    // Convex units: each face normal turned into the world, component-wise
    // |.|, for the body at hand: a box cell of half extents e reaches
    // |n|_world . e along the normal.
    std::vector<Eigen::Vector3d> abs_normals;
    std::vector<HalfSpace> cutting; // the planes that cut the cell at hand

    void check_bodies(const char *where) const {
        if (engine.body_count() != static_cast<int>(body_unit.size()))
            throw std::invalid_argument(std::string("Coupler::") + where + ": the engine has " +
                                        std::to_string(engine.body_count()) + " bodies, the coupler " +
                                        std::to_string(body_unit.size()));
    }
};

Coupler::Coupler(RigidBodyEngine &engine, std::vector<UnitTemplate> units, std::vector<int> body_unit,
                 CouplerSettings settings)
    : impl_(std::make_unique<Impl>(engine, std::move(units), std::move(body_unit), std::move(settings))) {
    const CouplerSettings &s = impl_->settings;
    if (!(s.smoothing_cells >= 0.0) || !std::isfinite(s.smoothing_cells))
        throw InputError("coupler: smoothing_cells must be >= 0");
    if (!(s.fluid_density > 0.0) || !std::isfinite(s.fluid_density))
        throw InputError("coupler: fluid_density must be > 0");
    if (!(s.added_mass_coefficient >= 0.0) || !std::isfinite(s.added_mass_coefficient))
        throw InputError("coupler: added_mass_coefficient must be >= 0");
    for (int u : impl_->body_unit)
        if (u < 0 || u >= static_cast<int>(impl_->units.size()))
            throw InputError("coupler: body refers to unknown unit " + std::to_string(u));
    impl_->check_bodies("Coupler");

    for (const UnitTemplate &unit : impl_->units) {
        if (s.added_mass_coefficient > 0.0 && !(unit.props.mass > 0.0 && unit.props.volume > 0.0))
            throw InputError("coupler: unit '" + unit.name + "' needs mass and volume for the added mass");
        UnitShape shape;
        if (s.mask == MaskSource::exact_shape) {
            if (unit.mesh.triangles.empty())
                throw InputError("coupler: unit '" + unit.name + "' has no exact mesh for the mask");
            for (const Eigen::Vector3d &v : unit.mesh.vertices)
                shape.outer = std::max(shape.outer, v.norm());
            // Cubes, the commonest unit, skip the triangle queries: at 100
            // units they were a third of the coupling's cost per step.
            shape.box = axis_aligned_box_half_extents(unit.mesh);
            if (s.fraction == SolidFraction::exact)
                shape.solid = std::make_unique<SolidShape>(SolidShape::from_mesh(unit.mesh));
            if (shape.box) {
                shape.inner = shape.box->minCoeff();
            } else {
                shape.query = std::make_unique<ShapeQuery>(unit.mesh);
                const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
                if (shape.query->inside(origin))
                    shape.inner = shape.query->distance(origin);
                // The mask asks within the ramp (half a cell, rarely more than
                // a third of the unit) of the surface; farther points go to
                // the tree.
                shape.near = std::make_unique<DistanceGrid>(unit.mesh, 0.5 * shape.outer);
            }
        } else {
            if (unit.clump.empty())
                throw InputError("coupler: unit '" + unit.name + "' has no clump spheres for the mask");
            shape.spheres = &unit.clump;
            double smallest = HUGE_VAL;
            for (const Sphere &sp : unit.clump) {
                shape.outer = std::max(shape.outer, sp.center.norm() + sp.radius);
                shape.inner = std::max(shape.inner, sp.radius - sp.center.norm());
                smallest = std::min(smallest, sp.radius);
            }
            if (s.fraction == SolidFraction::exact)
                shape.solid = std::make_unique<SolidShape>(
                    SolidShape::from_spheres(unit.clump, smallest / kSphereLinesPerRadius));
        }
        impl_->shapes.push_back(std::move(shape));
    }
    impl_->a_prev.assign(impl_->body_unit.size(), Eigen::Vector3d::Zero());
    impl_->alpha_prev.assign(impl_->body_unit.size(), Eigen::Vector3d::Zero());
    impl_->last_force.assign(impl_->body_unit.size(), Eigen::Vector3d::Constant(NAN));
    impl_->last_change.assign(impl_->body_unit.size(), Eigen::Vector3d::Zero());
    impl_->swings.assign(impl_->body_unit.size(), 0);
}

Coupler::~Coupler() = default;

// The exact fraction of cell i (circumradius `reach`) inside a unit at
// `position` whose frame `to_unit` turns world into unit axes; false when the
// cell lies wholly outside.
bool Coupler::Impl::exact_fraction(Impl &m, const UnitShape &shape, const CellSet &cells, std::size_t i,
                                   const Eigen::Vector3d &position, const Eigen::Matrix3d &to_unit,
                                   double reach, double &chi, Eigen::Vector3d &centroid) {
    const Eigen::Vector3d &half = m.bins.box_half[i];
    if (half.x() >= 0.0 && shape.solid->convex()) {
        // A box cell against a convex unit: wholly outside when a plane has
        // the whole box beyond it, inside when every plane has it within;
        // otherwise some plane cuts it.
        const Eigen::Vector3d x = to_unit * (cells.centres[i] - position);
        const std::vector<HalfSpace> &planes = shape.solid->planes();
        m.cutting.clear();
        for (std::size_t k = 0; k < planes.size(); ++k) {
            const double d = planes[k].normal.dot(x) - planes[k].offset, extent = m.abs_normals[k].dot(half);
            if (d >= extent)
                return false;
            if (d > -extent)
                m.cutting.push_back(planes[k]);
        }
        if (m.cutting.empty()) {
            chi = 1.0;
            return true;
        }
        cell_in_unit_frame(cells, i, half, position, to_unit, m.cell, m.cell_points);
        const SolidPart part =
            SolidShape::part_within(m.cell, m.cutting.data(), static_cast<int>(m.cutting.size()), m.scratch);
        if (!(part.volume > 0.0))
            return false;
        chi = std::min(1.0, part.volume / m.bins.cell_volume[i]);
        centroid = position + to_unit.transpose() * part.centroid;
        return true;
    } else {
        // One distance spares the clipping for cells that do not reach the
        // surface. Convex units: the largest plane distance, exact inside and
        // at most the true distance outside. Spheres: the depth inside is at
        // most the true depth. Both err on the side of clipping.
        const Eigen::Vector3d x = to_unit * (cells.centres[i] - position);
        const double d = shape.solid->convex() ? shape.solid->plane_distance(x) : shape.signed_distance(x);
        if (d >= reach)
            return false;
        if (d <= -reach) {
            chi = 1.0;
            return true;
        }
    }
    cell_in_unit_frame(cells, i, half, position, to_unit, m.cell, m.cell_points);
    const SolidPart part = shape.solid->part_inside(m.cell, m.scratch);
    if (!(part.volume > 0.0))
        return false;
    chi = std::min(1.0, part.volume / m.bins.cell_volume[i]);
    centroid = position + to_unit.transpose() * part.centroid;
    return true;
}

void Coupler::Impl::cells_of_body(int k, const CellSet &cells, BodyCells &own) {
    Impl &m = *this;
    own.cell.clear();
    own.chi.clear();
    own.centroid.clear();
    const UnitShape &shape = m.shapes[m.body_unit[k]];
    const Eigen::Vector3d p = m.states[k].pose.position;
    const Eigen::Quaterniond q_inv = m.states[k].pose.orientation.normalized().conjugate();
    const Eigen::Matrix3d to_unit = q_inv.toRotationMatrix();
    if (shape.solid && shape.solid->convex()) {
        m.abs_normals.clear();
        for (const HalfSpace &h : shape.solid->planes())
            m.abs_normals.push_back((to_unit.transpose() * h.normal).cwiseAbs());
    }
    const std::vector<double> &half_width = m.bins.half_width;
    const double body_reach = shape.outer + m.bins.max_half_width;
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
        lo[a] = m.bins.index(p - Eigen::Vector3d::Constant(body_reach), a);
        hi[a] = m.bins.index(p + Eigen::Vector3d::Constant(body_reach), a);
    }
    for (int bk = lo[2]; bk <= hi[2]; ++bk)
        for (int bj = lo[1]; bj <= hi[1]; ++bj)
            for (int bi = lo[0]; bi <= hi[0]; ++bi) {
                const int b = m.bins.bin(bi, bj, bk);
                for (int c = m.bins.first[b]; c < m.bins.first[b + 1]; ++c) {
                    const auto i = static_cast<std::size_t>(m.bins.cells[c]);
                    ++m.work.cells_visited;
                    const double hw = half_width[i];
                    const Eigen::Vector3d r = cells.centres[i] - p;
                    const double r2 = r.squaredNorm();
                    // Culling: beyond the bounding sphere plus the ramp (the
                    // cell's reach) chi is 0; inside the inscribed ball minus
                    // it, 1. Neither needs a query.
                    const double reach = shape.outer + hw;
                    if (r2 >= reach * reach)
                        continue;
                    double chi;
                    Eigen::Vector3d centroid = cells.centres[i];
                    const double core = shape.inner - hw;
                    if (core > 0.0 && r2 <= core * core) {
                        chi = 1.0;
                    } else {
                        ++m.work.cells_resolved;
                        if (!shape.solid)
                            chi = ramp(shape.signed_distance(q_inv * r), 2.0 * hw);
                        else if (!exact_fraction(m, shape, cells, i, p, to_unit, hw, chi, centroid))
                            continue;
                    }
                    if (chi > 0.0) {
                        own.cell.push_back(static_cast<int>(i));
                        own.chi.push_back(chi);
                        own.centroid.push_back(centroid);
                    }
                }
            }
}

const CellMask &Coupler::update_mask(const CellSet &cells) {
    Impl &m = *impl_;
    m.check_bodies("update_mask");
    const std::size_t n = cells.centres.size();
    if (cells.volumes.size() != n)
        throw std::invalid_argument("Coupler::update_mask: centres and volumes differ in size");

    const int nb = static_cast<int>(m.body_unit.size());
    m.states.resize(nb);
    for (int k = 0; k < nb; ++k)
        m.states[k] = m.engine.state(k);

    m.work = MaskWork{};
    const bool exact = m.settings.fraction == SolidFraction::exact;
    if (!m.bins.matches(cells)) {
        double largest_outer = 0.0;
        for (const UnitShape &shape : m.shapes)
            largest_outer = std::max(largest_outer, shape.outer);
        m.bins.build(cells, exact ? std::nullopt : std::optional<double>(m.settings.smoothing_cells),
                     largest_outer);
        m.body_cells.assign(static_cast<std::size_t>(nb), {});
    }
    m.body_cells.resize(static_cast<std::size_t>(nb));

    m.mask.chi.assign(n, 0.0);
    m.mask.body.assign(n, -1);
    m.mask.velocity.assign(n, Eigen::Vector3d::Zero());
    m.mask.centroid.resize(n); // set where a body owns the cell
    if (n == 0)
        return m.mask;

    for (int k = 0; k < nb; ++k) {
        Impl::BodyCells &own = m.body_cells[k];
        const Pose &pose = m.states[k].pose;
        const UnitShape &shape = m.shapes[m.body_unit[k]];
        // Exact fractions of a unit that has not moved by more than
        // kRestTolerance of the smallest cell (at its farthest point) since
        // they were computed are kept (see kRestTolerance).
        const bool at_rest = exact && own.valid &&
                             (pose.position - own.pose.position).norm() +
                                     shape.outer * pose.orientation.angularDistance(own.pose.orientation) <=
                                 kRestTolerance * m.bins.smallest_cell;
        if (!at_rest) {
            ++m.work.bodies_recomputed;
            m.cells_of_body(k, cells, own);
            own.pose = pose;
            own.valid = true;
        }
        for (std::size_t e = 0; e < own.cell.size(); ++e) {
            const auto i = static_cast<std::size_t>(own.cell[e]);
            if (own.chi[e] > m.mask.chi[i]) {
                m.mask.chi[i] = own.chi[e];
                m.mask.body[i] = k;
                m.mask.centroid[i] = own.centroid[e];
            }
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        const int k = m.mask.body[i];
        if (k < 0)
            continue;
        const BodyState &s = m.states[k];
        m.mask.velocity[i] = s.velocity + s.angular_velocity.cross(cells.centres[i] - s.pose.position);
    }
    return m.mask;
}

const Coupler::MaskWork &Coupler::last_mask_work() const {
    return impl_->work;
}

BodyLoads Coupler::integrate_loads(const CellSet &cells,
                                   const std::vector<Eigen::Vector3d> &force_density) const {
    const Impl &m = *impl_;
    const std::size_t n = cells.centres.size();
    if (m.mask.chi.size() != n || cells.volumes.size() != n || force_density.size() != n)
        throw std::invalid_argument("Coupler::integrate_loads: the cells, their force density and the last "
                                    "mask must have the same size (call update_mask first)");
    const std::size_t nb = m.body_unit.size();
    BodyLoads loads;
    loads.force.assign(nb, Eigen::Vector3d::Zero());
    loads.torque.assign(nb, Eigen::Vector3d::Zero());
    loads.mask_volume.assign(nb, 0.0);
    loads.mask_first_moment.assign(nb, Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < n; ++i) {
        const int k = m.mask.body[i];
        if (k < 0)
            continue;
        const double chi_v = m.mask.chi[i] * cells.volumes[i];
        const Eigen::Vector3d r = m.mask.centroid[i] - m.states[k].pose.position;
        const Eigen::Vector3d f = chi_v * force_density[i];
        loads.force[k] += f;
        loads.torque[k] += r.cross(f);
        loads.mask_volume[k] += chi_v;
        loads.mask_first_moment[k] += chi_v * r;
    }
    return loads;
}

void centre_torque_on_mask(BodyLoads &loads) {
    const std::size_t nb = loads.force.size();
    if (loads.torque.size() != nb || loads.mask_volume.size() != nb || loads.mask_first_moment.size() != nb)
        throw std::invalid_argument("centre_torque_on_mask: loads for different numbers of bodies");
    for (std::size_t k = 0; k < nb; ++k)
        if (loads.mask_volume[k] > 0.0)
            loads.torque[k] -= (loads.mask_first_moment[k] / loads.mask_volume[k]).cross(loads.force[k]);
}

// A partitioned exchange that has gone unstable shows one signature: the
// fluid load on a unit swings to the opposite side every fluid step and
// grows (the recurrence in the notes at the top, amplification below -1).
// Measured on a LIGGGHTS cube resting on a tank floor (soft contacts: it
// vibrates, squeezing the fluid between it and the floor), the load went
// 78, 850, -1233, 3907, -12223, 44585 N on a 188 N cube, then 4e5 N. No wave
// does that, so three flipped-and-grown changes in a row, the last above
// five times the unit's weight, stop the run with the reason, long before
// the numbers become absurd.
// Tested without arithmetic on the values: OpenFOAM traps floating point
// exceptions (FOAM_SIGFPE), and Eigen's allFinite() computes inf - inf, the
// norm of 1e160 N overflows. Beyond 1e100 N nothing physical is left.
namespace {
bool is_sane_load(const Eigen::Vector3d &v) {
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(v[c]) || std::abs(v[c]) > 1e100)
            return false;
    return true;
}
} // namespace

void Coupler::check_stability(const BodyLoads &total) {
    Impl &m = *impl_;
    for (std::size_t k = 0; k < m.body_unit.size(); ++k) {
        const Eigen::Vector3d &force = total.force[k];
        if (!is_sane_load(force) || !is_sane_load(total.torque[k]))
            throw std::runtime_error("coupling: the fluid load on body " + std::to_string(k) +
                                     " is not finite or beyond 1e100 (the fluid solution has blown up)");
        const Eigen::Vector3d change = is_sane_load(m.last_force[k])
                                           ? Eigen::Vector3d(force - m.last_force[k])
                                           : Eigen::Vector3d::Zero();
        const Eigen::Vector3d before = m.last_change[k];
        const bool flipped = change.dot(before) < -0.5 * change.norm() * before.norm();
        const bool grew = change.norm() > 1.5 * before.norm();
        m.swings[k] = flipped && grew ? m.swings[k] + 1 : 0;
        m.last_force[k] = force;
        m.last_change[k] = change;
        const MassProperties &props = m.units[m.body_unit[k]].props;
        const double weight = props.mass * m.settings.gravity.norm();
        if (m.swings[k] >= 3 && change.norm() > 5.0 * weight) {
            char growth[32];
            std::snprintf(growth, sizeof growth, "%.2g", change.norm() / before.norm());
            throw std::runtime_error(
                "coupling unstable at body " + std::to_string(k) + " ('" + m.units[m.body_unit[k]].name +
                "'): its fluid load swings to the opposite side every fluid step and grows (step change " +
                std::to_string(static_cast<long>(change.norm())) + " N, x" + growth + " per step, weight " +
                std::to_string(static_cast<long>(weight)) +
                " N). Typical causes: a unit moving against a wall or the mesh's edge, squeezing the "
                "fluid between them (lower fluid.penalty; LIGGGHTS' soft contacts vibrate there, engine "
                "bullet does not), or a light unit without enough fluid.added_mass");
        }
    }
}

void Coupler::advance(const BodyLoads &total, double dt_fluid) {
    Impl &m = *impl_;
    m.check_bodies("advance");
    const int nb = static_cast<int>(m.body_unit.size());
    if (static_cast<int>(total.force.size()) != nb || static_cast<int>(total.torque.size()) != nb)
        throw std::invalid_argument("Coupler::advance: loads for " + std::to_string(total.force.size()) +
                                    " bodies, the engine has " + std::to_string(nb));
    if (!(dt_fluid > 0.0))
        throw std::invalid_argument("Coupler::advance: dt_fluid must be > 0");

    check_stability(total);
    const double C_a = m.settings.added_mass_coefficient;
    std::vector<Eigen::Vector3d> v0(nb), w0(nb);
    for (int k = 0; k < nb; ++k) {
        const BodyState s = m.engine.state(k);
        v0[k] = s.velocity;
        w0[k] = s.angular_velocity;
        Eigen::Vector3d force = total.force[k];
        Eigen::Vector3d torque = total.torque[k];
        if (C_a > 0.0) {
            // See the derivation at the top of this file.
            const MassProperties &props = m.units[m.body_unit[k]].props;
            const double mass = props.mass;
            const double m_a = C_a * m.settings.fluid_density * props.volume;
            const Eigen::Matrix3d R = s.pose.orientation.normalized().toRotationMatrix();
            const Eigen::Matrix3d I_w = R * props.inertia * R.transpose();
            force = (mass * (force + m_a * m.a_prev[k]) - m_a * mass * m.settings.gravity) / (mass + m_a);
            torque = (mass * torque + m_a * (I_w * m.alpha_prev[k])) / (mass + m_a);
        }
        m.engine.set_external_load(k, force, torque);
    }
    const double t0 = m.engine.time();
    m.engine.advance(dt_fluid);
    // The engine advances in whole steps: the span actually run is what the
    // velocities changed over.
    const double elapsed = m.engine.time() - t0;
    if (elapsed > 0.0) {
        for (int k = 0; k < nb; ++k) {
            const BodyState s = m.engine.state(k);
            m.a_prev[k] = (s.velocity - v0[k]) / elapsed;
            m.alpha_prev[k] = (s.angular_velocity - w0[k]) / elapsed;
        }
    }
}

std::vector<double> Coupler::state() const {
    const Impl &m = *impl_;
    std::vector<double> v;
    for (std::size_t k = 0; k < m.body_unit.size(); ++k) {
        for (const Eigen::Vector3d *x : {&m.a_prev[k], &m.alpha_prev[k], &m.last_force[k], &m.last_change[k]})
            v.insert(v.end(), x->data(), x->data() + 3);
        v.push_back(m.swings[k]);
    }
    return v;
}

void Coupler::set_state(const std::vector<double> &values) {
    Impl &m = *impl_;
    if (values.size() != 13 * m.body_unit.size())
        throw InputError("coupler state: " + std::to_string(values.size()) + " values for " +
                         std::to_string(m.body_unit.size()) + " bodies (another scene?)");
    const double *x = values.data();
    for (std::size_t k = 0; k < m.body_unit.size(); ++k) {
        for (Eigen::Vector3d *y : {&m.a_prev[k], &m.alpha_prev[k], &m.last_force[k], &m.last_change[k]}) {
            *y = Eigen::Vector3d(x[0], x[1], x[2]);
            x += 3;
        }
        m.swings[k] = static_cast<int>(*x++);
    }
    forget_kept_fractions();
}

void Coupler::forget_kept_fractions() {
    for (Impl::BodyCells &own : impl_->body_cells)
        own.valid = false;
}

} // namespace armour
