/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourExchange.H"

#include "scene_setup.h"

#include <filesystem>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

// This rank's cells for the coupler, with their faces for the exact solid
// fractions; copied once: the mesh is static.
armour::CellSet cellSet(const Foam::fvMesh& mesh)
{
    armour::CellSet cells;
    const Foam::vectorField& C = mesh.C();
    const Foam::scalarField& V = mesh.V();
    cells.centres.resize(C.size());
    cells.volumes.resize(C.size());
    forAll(C, i)
    {
        cells.centres[i] = armourFoam::toEigen(C[i]);
        cells.volumes[i] = V[i];
    }
    const Foam::pointField& points = mesh.points();
    cells.points.resize(points.size());
    forAll(points, i)
    {
        cells.points[i] = armourFoam::toEigen(points[i]);
    }
    const Foam::faceList& faces = mesh.faces();
    cells.faces.resize(faces.size());
    forAll(faces, f)
    {
        cells.faces[f].assign(faces[f].begin(), faces[f].end());
    }
    // A face's points run counter-clockwise seen from outside its owner, so
    // its neighbour lists it reversed (~f).
    const Foam::cellList& cellFaces = mesh.cells();
    const Foam::labelList& owner = mesh.faceOwner();
    cells.cell_faces.resize(cellFaces.size());
    forAll(cellFaces, i)
    {
        for (const Foam::label f : cellFaces[i])
        {
            cells.cell_faces[i].push_back(owner[f] == i ? f : ~f);
        }
    }
    return cells;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

Eigen::Vector3d armourFoam::toEigen(const Foam::vector& v)
{
    return Eigen::Vector3d(v.x(), v.y(), v.z());
}


Foam::vector armourFoam::toFoam(const Eigen::Vector3d& v)
{
    return Foam::vector(v.x(), v.y(), v.z());
}


armourFoam::stepLoads armourFoam::stepLoads::zero(std::size_t bodies)
{
    stepLoads s;
    s.loads.force.assign(bodies, Eigen::Vector3d::Zero());
    s.loads.torque.assign(bodies, Eigen::Vector3d::Zero());
    s.loads.mask_volume.assign(bodies, 0.0);
    s.loads.mask_first_moment.assign(bodies, Eigen::Vector3d::Zero());
    s.source.assign(bodies, Eigen::Vector3d::Zero());
    s.chiVolume.assign(bodies, 0.0);
    return s;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

armourFoam::bodyExchange::bodyExchange
(
    const armour::Scene& scene,
    const std::string& cacheDir,
    const Foam::fvMesh& mesh,
    const Eigen::Vector3d& gravity
)
{
    armour::SceneSetup setup = armour::build_scene(scene, cacheDir, false);
    setup.settings.work_dir = mesh.time().globalPath()/"armourEngine";
    engine_ = armour::make_engine(scene.engine, setup.settings);
    for (const armour::UnitTemplate& u : setup.units)
    {
        engine_->add_template(u);
    }
    for (const armour::Wall& w : setup.walls)
    {
        engine_->add_wall(w);
    }
    for (const armour::BodyInit& b : setup.bodies)
    {
        engine_->add_body(b);
        bodyUnit_.push_back(b.unit);
        names_.push_back
        (
            setup.units[b.unit].name + "_" + std::to_string(names_.size())
        );
    }

    const armour::SceneFluid& fluid = *scene.fluid;
    armour::CouplerSettings cs;
    cs.mask =
        fluid.mask == "spheres"
      ? armour::MaskSource::clump_spheres
      : armour::MaskSource::exact_shape;
    cs.fraction =
        fluid.solid_fraction == "ramp"
      ? armour::SolidFraction::sampled_ramp
      : armour::SolidFraction::exact;
    cs.smoothing_cells = fluid.smoothing_cells;
    cs.fluid_density = fluid.fluid_density;
    cs.added_mass_coefficient = fluid.added_mass;
    cs.gravity = gravity;

    units_ = setup.units;
    coupler_.reset(new armour::Coupler(*engine_, setup.units, bodyUnit_, cs));
    cells_ = cellSet(mesh);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

const armour::CellMask& armourFoam::bodyExchange::updateMask()
{
    const armour::CellMask& mask = coupler_->update_mask(cells_);
    body_ = mask.body;
    return mask;
}


armourFoam::stepLoads armourFoam::bodyExchange::sumLoads
(
    const std::vector<Eigen::Vector3d>& forceDensity,
    const Foam::volScalarField& rho,
    const Foam::volVectorField& U,
    const Foam::volScalarField& chi,
    const Foam::volVectorField& UBody,
    Foam::scalar penalty
)
{
    using namespace Foam;
    const label nb = names_.size();
    const scalarField& V = U.mesh().V();
    stepLoads s;
    s.loads = coupler_->integrate_loads(cells_, forceDensity);

    // One buffer per body, F M S chiVolume, and the mask's volume and first
    // moment beside it: the torque is taken about the mask's centroid once
    // they are summed over the ranks.
    List<scalar> buf(10*nb, Zero);
    forAll(U, i)
    {
        const label k = body_[i];
        if (k < 0)
        {
            continue;
        }
        const vector S = -rho[i]*penalty*chi[i]*(U[i] - UBody[i])*V[i];
        for (direction c = 0; c < 3; ++c)
        {
            buf[10*k + 6 + c] += S[c];
        }
        buf[10*k + 9] += chi[i]*V[i];
    }
    List<scalar> mask(4*nb, Zero);
    for (label k = 0; k < nb; ++k)
    {
        for (direction c = 0; c < 3; ++c)
        {
            buf[10*k + c] = s.loads.force[k][c];
            buf[10*k + 3 + c] = s.loads.torque[k][c];
            mask[4*k + c] = s.loads.mask_first_moment[k][c];
        }
        mask[4*k + 3] = s.loads.mask_volume[k];
    }
    // Every rank gets the same totals, so every rank's engine replica takes
    // the same step.
    Pstream::listCombineGather(buf, plusEqOp<scalar>());
    Pstream::listCombineScatter(buf);
    Pstream::listCombineGather(mask, plusEqOp<scalar>());
    Pstream::listCombineScatter(mask);
    s.source.resize(nb);
    s.chiVolume.resize(nb);
    for (label k = 0; k < nb; ++k)
    {
        for (direction c = 0; c < 3; ++c)
        {
            s.loads.force[k][c] = buf[10*k + c];
            s.loads.torque[k][c] = buf[10*k + 3 + c];
            s.loads.mask_first_moment[k][c] = mask[4*k + c];
            s.source[k][c] = buf[10*k + 6 + c];
        }
        s.loads.mask_volume[k] = mask[4*k + 3];
        s.chiVolume[k] = buf[10*k + 9];
    }
    armour::centre_torque_on_mask(s.loads);
    return s;
}


void armourFoam::bodyExchange::advance
(
    const armour::BodyLoads& loads,
    double deltaT
)
{
    coupler_->advance(loads, deltaT);
}


void armourFoam::bodyExchange::saveState(const std::string& dir) const
{
    std::filesystem::create_directories(dir + "/engine");
    engine_->save_state(dir + "/engine");
    armour::write_state_values(dir + "/coupler", coupler_->state());
}


void armourFoam::bodyExchange::loadState(const std::string& dir)
{
    engine_->load_state(dir + "/engine");
    coupler_->set_state(armour::read_state_values(dir + "/coupler"));
}


void armourFoam::bodyExchange::restartPoint()
{
    coupler_->forget_kept_fractions();
}


void armourFoam::bodyExchange::checkReplicas(double t)
{
    // The replicas only stay one run if the engine is deterministic (same
    // summed loads in, same bits out); a rank that drifted would put its
    // bodies elsewhere in its own cells. Checked as the spread of every
    // state component over the ranks.
    using namespace Foam;
    const label nb = names_.size();
    List<scalar> hi(13*nb, Zero);
    for (label k = 0; k < nb; ++k)
    {
        const armour::BodyState s = engine_->state(k);
        const Eigen::Quaterniond& q = s.pose.orientation;
        const scalar state[13] =
        {
            s.pose.position.x(), s.pose.position.y(), s.pose.position.z(),
            q.w(), q.x(), q.y(), q.z(),
            s.velocity.x(), s.velocity.y(), s.velocity.z(),
            s.angular_velocity.x(), s.angular_velocity.y(),
            s.angular_velocity.z()
        };
        for (label c = 0; c < 13; ++c)
        {
            hi[13*k + c] = state[c];
        }
    }
    List<scalar> lo(hi);
    Pstream::listCombineGather(hi, maxEqOp<scalar>());
    Pstream::listCombineGather(lo, minEqOp<scalar>());
    if (!Pstream::master())
    {
        return;
    }
    const bool wasIdentical = replicasIdentical_;
    forAll(hi, i)
    {
        if (!(hi[i] == lo[i]))
        {
            replicasIdentical_ = false;
        }
        if (i % 13 < 3)
        {
            replicaSpread_ = max(replicaSpread_, hi[i] - lo[i]);
        }
    }
    if (wasIdentical && !replicasIdentical_)
    {
        WarningInFunction
            << "armour: the ranks' engine replicas differ at t = "
            << t << " s (positions by up to " << replicaSpread_
            << " m), so the ranks no longer run one simulation (an"
            << " engine that is not deterministic?); the record is the"
            << " master rank's" << endl;
    }
}


// ************************************************************************* //
