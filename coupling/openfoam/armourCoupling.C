/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourCoupling.H"
#include "armourCouplingSide.H"
#include "armourForceDensity.H"

#include "addToRunTimeSelectionTable.H"
#include "fvMatrices.H"
#include "fvMesh.H"
#include "fvcGrad.H"
#include "fvcLaplacian.H"
#include "fvmSup.H"
#include "uniformDimensionedFields.H"

// The armour side: plain C++ and Eigen, no OpenFOAM type crosses these.
#include "body_recorder.h"
#include "clump.h"
#include "coupler.h"
#include "engine_registry.h"
#include "scene.h"
#include "scene_setup.h"
#include "shapes.h"

#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

// * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * * //

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(armourCoupling, 0);
    addToRunTimeSelectionTable(option, armourCoupling, dictionary);
}
}




using namespace Foam::armourFoam;


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::fv::armourCoupling::armourCoupling
(
    const word& name,
    const word& modelType,
    const dictionary& dict,
    const fvMesh& mesh
)
:
    option(name, modelType, dict, mesh),
    armour_(new armourSide),
    penalty_(coeffs_.lookupOrDefault<scalar>("penalty", 0)),
    chi_
    (
        IOobject
        (
            "armourChi",
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedScalar(dimless, Zero)
    ),
    UBody_
    (
        IOobject
        (
            "armourUBody",
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedVector(dimVelocity, Zero)
    ),
    lastTimeIndex_(mesh.time().timeIndex())
{
    fieldNames_ = wordList(1, "U");
    applied_.setSize(fieldNames_.size(), false);

    if (!coeffs_.found("scene"))
    {
        FatalIOErrorInFunction(coeffs_)
            << "armourCouplingCoeffs needs 'scene' (an armour scene file with"
            << " a [fluid] table; `armour run` writes it)" << exit(FatalIOError);
    }
    constructFromScene(fileName(coeffs_.get<fileName>("scene")));
}


Foam::fv::armourCoupling::~armourCoupling()
{}


// * * * * * * * * * * * * * * * Private Functions * * * * * * * * * * * * * //

void Foam::fv::armourCoupling::constructFromScene(const fileName& scenePath)
{
    const Time& runTime = mesh_.time();
    std::string engineName;
    try
    {
        // Every rank reads the same resolved scene and builds the same
        // engine: identical replicas fed with the same summed loads.
        const armour::Scene scene = armour::load_scene(scenePath);
        if (!scene.fluid)
        {
            FatalIOErrorInFunction(coeffs_)
                << "scene " << scenePath << " has no [fluid] table"
                << exit(FatalIOError);
        }
        const armour::SceneFluid& fluid = *scene.fluid;
        penalty_ = fluid.penalty;
        engineName = scene.engine;
        armour_->frozen = fluid.frozen;

        // The fluid and the engine must feel the same gravity.
        const Eigen::Vector3d gravity = toEigen
        (
            runTime.lookupObject<uniformDimensionedVectorField>("g").value()
        );
        if ((gravity - scene.gravity).norm() > 1e-9*scene.gravity.norm())
        {
            FatalIOErrorInFunction(coeffs_)
                << "constant/g " << toFoam(gravity)
                << " differs from the scene's run.gravity "
                << toFoam(scene.gravity) << exit(FatalIOError);
        }

        const std::string cache =
            coeffs_.lookupOrDefault<fileName>
            (
                "cache",
                fileName(armour::default_cache_dir())
            );
        armour::SceneSetup setup = armour::build_scene(scene, cache, false);
        setup.settings.work_dir = runTime.globalPath()/"armourEngine";
        armour_->engine = armour::make_engine(scene.engine, setup.settings);
        for (const armour::UnitTemplate& u : setup.units)
        {
            armour_->engine->add_template(u);
        }
        for (const armour::Wall& w : setup.walls)
        {
            armour_->engine->add_wall(w);
        }
        std::vector<int> bodyUnit;
        for (const armour::BodyInit& b : setup.bodies)
        {
            armour_->engine->add_body(b);
            bodyUnit.push_back(b.unit);
            armour_->names.push_back
            (
                setup.units[b.unit].name + "_"
              + std::to_string(armour_->names.size())
            );
        }

        armour::CouplerSettings cs;
        cs.mask =
            fluid.mask == "spheres"
          ? armour::MaskSource::clump_spheres
          : armour::MaskSource::exact_shape;
        cs.smoothing_cells = fluid.smoothing_cells;
        cs.fluid_density = fluid.fluid_density;
        cs.added_mass_coefficient = fluid.added_mass;
        cs.gravity = gravity;

        std::vector<armour::RecorderUnit> recorderUnits;
        for (const armour::UnitTemplate& u : setup.units)
        {
            recorderUnits.push_back({u.name, u.mesh});
        }
        armour_->coupler.reset
        (
            new armour::Coupler(*armour_->engine, setup.units, bodyUnit, cs)
        );

        armour_->cells = cellSet(mesh_);
        updateFields();

        // The record sits beside the scene it ran (the run's output
        // folder), unless the dictionary names another folder.
        if (Pstream::master())
        {
            const fileName outDir =
                coeffs_.lookupOrDefault<fileName>("output", scenePath.path());
            const armour::TimeStepReport dt =
                armour_->engine->time_step_report();
            armour_->recorder.reset
            (
                new armour::BodyRecorder
                (
                    outDir/"bodies.h5",
                    outDir/"bodies.xdmf",
                    recorderUnits,
                    bodyUnit,
                    {
                        {"scene", scene.name},
                        {"engine", armour_->engine->name()},
                        {"dt", std::to_string(dt.used)},
                        {"coupling", "interFoam armourCoupling"},
                        {"external_force", "fluid load F (without gravity)"}
                    }
                )
            );
            std::vector<armour::BodyState> states;
            for (int k = 0; k < armour_->engine->body_count(); ++k)
            {
                states.push_back(armour_->engine->state(k));
                states.back().external_force.setZero();
                states.back().external_torque.setZero();
            }
            armour_->recorder->append(runTime.value(), states);

            // The free surface a floating unit settles against moves with
            // the water it displaces and with what seeps into its ramp
            // cells; the water volume outside the units pins it down.
            armour_->timesFile = outDir/"coupling_times.json";
            armour_->fluidCsv.open(outDir/"fluid.csv");
            armour_->fluidCsv
                << "time,water_volume,water_volume_outside_units\n"
                << std::setprecision(12);
        }
        // On every rank: the record times decide collective reductions.
        armour_->recordInterval = scene.output_interval;
        armour_->nextRecord = runTime.value() + scene.output_interval;
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "armour: " << err.what() << exit(FatalError);
    }

    if (Pstream::master() && coeffs_.found("csv"))
    {
        openCsv(runTime.globalPath()/coeffs_.get<fileName>("csv"));
    }

    Info<< "    armourCoupling: scene " << scenePath << ", "
        << armour_->names.size() << " bodies, engine " << engineName
        << ", K = " << penalty_ << " 1/s"
        << (armour_->frozen ? ", frozen (mask only)" : "") << endl;
}


void Foam::fv::armourCoupling::openCsv(const fileName& csvName)
{
    armour_->csv.open(csvName);
    if (!armour_->csv)
    {
        FatalErrorInFunction
            << "cannot write " << csvName << exit(FatalError);
    }
    armour_->csv
        << "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,"
           "Fx,Fy,Fz,Mx,My,Mz,Sx,Sy,Sz,chiVolume,engineTime\n";
    armour_->csv << std::setprecision(10);
}


void Foam::fv::armourCoupling::updateFields()
{
    const armour::CellMask& mask = armour_->coupler->update_mask(armour_->cells);
    scalarField& chi = chi_.primitiveFieldRef();
    vectorField& Ub = UBody_.primitiveFieldRef();
    forAll(chi, i)
    {
        chi[i] = mask.chi[i];
        Ub[i] = toFoam(mask.velocity[i]);
    }
    armour_->body = mask.body;
    chi_.correctBoundaryConditions();
    UBody_.correctBoundaryConditions();
}


void Foam::fv::armourCoupling::couple
(
    const volScalarField& rho,
    const volVectorField& U
)
{
    const Time& runTime = mesh_.time();
    using clock = std::chrono::steady_clock;
    const auto seconds = [](clock::time_point a, clock::time_point b)
    {
        return std::chrono::duration<double>(b - a).count();
    };
    const clock::time_point t0 = clock::now();
    const label nb = armour_->names.size();
    ++armour_->steps;
    List<scalar> buf(10*nb, Zero);
    if (!armour_->frozen)
    {
        const volScalarField& p = mesh_.lookupObject<volScalarField>("p");

        // mu_eff = rho (nu + nut); nut only where a turbulence model made one.
        volScalarField muEff
        (
            "armourMuEff",
            rho*mesh_.lookupObject<volScalarField>("nu")
        );
        if (mesh_.foundObject<volScalarField>("nut"))
        {
            muEff += rho*mesh_.lookupObject<volScalarField>("nut");
        }
        using method = armourSide::forceDensityMethod;
        if (armour_->method == method::unchecked)
        {
            const bool agrees = forceDensityAgrees(mesh_, muEff);
            armour_->method = agrees ? method::faceByFace : method::fvc;
            Info<< "    armourCoupling: force density "
                << (agrees
                    ? "face by face in the units' cells (checked against fvc)"
                    : "by fvc on the whole mesh (the face-by-face sum differs "
                      "from fvc here: non-orthogonal mesh or other schemes)")
                << endl;
        }
        std::vector<Eigen::Vector3d>& fd = armour_->forceDensity;
        fd.assign(mesh_.nCells(), Eigen::Vector3d::Zero());
        if (armour_->method == method::faceByFace)
        {
            DynamicList<label> cells(mesh_.nCells()/8);
            forAll(armour_->body, i)
            {
                if (armour_->body[i] >= 0)
                {
                    cells.append(i);
                }
            }
            vectorField f(cells.size());
            faceByFaceForceDensity(mesh_, p, muEff, U, cells, f);
            forAll(cells, k)
            {
                fd[cells[k]] = toEigen(f[k]);
            }
        }
        else
        {
            const volVectorField f(fvcForceDensity(p, muEff, U));
            forAll(f, i)
            {
                fd[i] = toEigen(f[i]);
            }
        }

        armour::BodyLoads loads;
        try
        {
            loads = armour_->coupler->integrate_loads(armour_->cells, fd);
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
        }

        // The momentum source each body puts into the fluid, at the same fields:
        // with the loads, it checks the coupling's force balance.
        forAll(U, i)
        {
            const label k = armour_->body[i];
            if (k < 0)
            {
                continue;
            }
            const vector S =
                -rho[i]*penalty_*chi_[i]*(U[i] - UBody_[i])*mesh_.V()[i];
            for (direction c = 0; c < 3; ++c)
            {
                buf[10*k + 6 + c] += S[c];
            }
            buf[10*k + 9] += chi_[i]*mesh_.V()[i];
        }
        // The mask's volume and first moment travel with the loads: the
        // torque is taken about the mask's centroid once they are summed.
        List<scalar> mask(4*nb, Zero);
        for (label k = 0; k < nb; ++k)
        {
            for (direction c = 0; c < 3; ++c)
            {
                buf[10*k + c] = loads.force[k][c];
                buf[10*k + 3 + c] = loads.torque[k][c];
                mask[4*k + c] = loads.mask_first_moment[k][c];
            }
            mask[4*k + 3] = loads.mask_volume[k];
        }
        // Every rank gets the same totals, so every rank's engine replica
        // (free_body, bullet, or a serial LIGGGHTS per rank) takes the same
        // step.
        Pstream::listCombineGather(buf, plusEqOp<scalar>());
        Pstream::listCombineScatter(buf);
        Pstream::listCombineGather(mask, plusEqOp<scalar>());
        Pstream::listCombineScatter(mask);
        for (label k = 0; k < nb; ++k)
        {
            for (direction c = 0; c < 3; ++c)
            {
                loads.force[k][c] = buf[10*k + c];
                loads.torque[k][c] = buf[10*k + 3 + c];
                loads.mask_first_moment[k][c] = mask[4*k + c];
            }
            loads.mask_volume[k] = mask[4*k + 3];
        }
        armour::centre_torque_on_mask(loads);
        // What is recorded is what is applied.
        for (label k = 0; k < nb; ++k)
        {
            for (direction c = 0; c < 3; ++c)
            {
                buf[10*k + 3 + c] = loads.torque[k][c];
            }
        }

        const clock::time_point t1 = clock::now();
        try
        {
            armour_->coupler->advance(loads, runTime.deltaTValue());
            const clock::time_point t2 = clock::now();
            updateFields();
            armour_->loadSeconds += seconds(t0, t1);
            armour_->demSeconds += seconds(t1, t2);
            armour_->maskSeconds += seconds(t2, clock::now());
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
        }
    }

    // Every record interval and at the last step, so the record ends where
    // the run does.
    const double t = runTime.value();
    const double dtF = runTime.deltaTValue();
    const bool recordNow =
        armour_->recordInterval > 0
     && (
            t >= armour_->nextRecord - 1e-6*dtF
         || t + 0.5*dtF >= runTime.endTime().value()
        );
    scalar water = 0;
    scalar waterOutside = 0;
    if (recordNow)
    {
        if (mesh_.foundObject<volScalarField>("alpha.water"))
        {
            const volScalarField& alpha =
                mesh_.lookupObject<volScalarField>("alpha.water");
            forAll(alpha, i)
            {
                water += alpha[i]*mesh_.V()[i];
                waterOutside += alpha[i]*(1 - chi_[i])*mesh_.V()[i];
            }
        }
        reduce(water, sumOp<scalar>());
        reduce(waterOutside, sumOp<scalar>());
        while (armour_->nextRecord <= t + 1e-6*dtF)
        {
            armour_->nextRecord += armour_->recordInterval;
        }
    }
    if (recordNow && Pstream::parRun())
    {
        // The replicas only stay one run if the engine is deterministic
        // (same summed loads in, same bits out); a rank that drifted would
        // put its bodies elsewhere in its own cells. Checked at each record:
        // the spread of every state component over the ranks.
        List<scalar> hi(13*nb, Zero);
        for (label k = 0; k < nb; ++k)
        {
            const armour::BodyState s = armour_->engine->state(k);
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
        if (Pstream::master())
        {
            const bool wasIdentical = armour_->replicasIdentical;
            forAll(hi, i)
            {
                if (!(hi[i] == lo[i]))
                {
                    armour_->replicasIdentical = false;
                }
                if (i % 13 < 3)
                {
                    armour_->replicaSpread =
                        max(armour_->replicaSpread, hi[i] - lo[i]);
                }
            }
            if (wasIdentical && !armour_->replicasIdentical)
            {
                WarningInFunction
                    << "armour: the ranks' engine replicas differ at t = "
                    << t << " s (positions by up to " << armour_->replicaSpread
                    << " m), so the ranks no longer run one simulation (an"
                    << " engine that is not deterministic?); the record is the"
                    << " master rank's" << endl;
            }
        }
    }
    if (recordNow && armour_->recorder)
    {
        std::vector<armour::BodyState> states;
        for (label k = 0; k < nb; ++k)
        {
            states.push_back(armour_->engine->state(k));
            states.back().external_force =
                Eigen::Vector3d(buf[10*k], buf[10*k + 1], buf[10*k + 2]);
            states.back().external_torque =
                Eigen::Vector3d(buf[10*k + 3], buf[10*k + 4], buf[10*k + 5]);
        }
        try
        {
            armour_->recorder->append(t, states);
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
        }
        armour_->fluidCsv
            << t << ',' << water << ',' << waterOutside << std::endl;
        std::ofstream times(armour_->timesFile);
        times
            << std::setprecision(9)
            << "{\"frozen\": " << (armour_->frozen ? "true" : "false")
            << ", \"coupling_steps\": " << armour_->steps
            << ", \"load_seconds\": " << armour_->loadSeconds
            << ", \"dem_seconds\": " << armour_->demSeconds
            << ", \"mask_seconds\": " << armour_->maskSeconds
            << ", \"replicas_identical\": "
            << (armour_->replicasIdentical ? "true" : "false")
            << ", \"replica_position_spread\": " << armour_->replicaSpread
            // Both clocks start at 0 (the cases' startTime); the engine keeps
            // the fluid's to half an engine step (frozen runs never advance).
            << std::setprecision(17)
            << ", \"fluid_time\": " << t
            << ", \"engine_time\": " << armour_->engine->time()
            << ", \"engine_time_step\": " << armour_->engine->time_step()
            << "}\n";
    }

    if (Pstream::master() && armour_->csv.is_open())
    {
        std::ofstream& out = armour_->csv;
        for (label k = 0; k < nb; ++k)
        {
            const armour::BodyState s = armour_->engine->state(k);
            const Eigen::Quaterniond& q = s.pose.orientation;
            out << runTime.value() << ',' << armour_->names[k] << ','
                << s.pose.position.x() << ',' << s.pose.position.y() << ','
                << s.pose.position.z() << ','
                << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ','
                << s.velocity.x() << ',' << s.velocity.y() << ','
                << s.velocity.z() << ','
                << s.angular_velocity.x() << ',' << s.angular_velocity.y()
                << ',' << s.angular_velocity.z();
            for (label c = 0; c < 10; ++c)
            {
                out << ',' << buf[10*k + c];
            }
            out << ',' << armour_->engine->time() << '\n';
        }
        out.flush();
    }

    if (log)
    {
        for (label k = 0; k < nb; ++k)
        {
            Info<< "    armour " << armour_->names[k] << ": F = ("
                << buf[10*k] << ' ' << buf[10*k + 1] << ' ' << buf[10*k + 2]
                << ") N, S = (" << buf[10*k + 6] << ' ' << buf[10*k + 7]
                << ' ' << buf[10*k + 8] << ") N" << endl;
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::fv::armourCoupling::addSup
(
    const volScalarField& rho,
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    const volVectorField& U = eqn.psi();

    // Once per time step, not per PIMPLE outer corrector: the engine must
    // take exactly one step of deltaT.
    if (mesh_.time().timeIndex() != lastTimeIndex_)
    {
        lastTimeIndex_ = mesh_.time().timeIndex();
        couple(rho, U);
    }

    const volScalarField rhoKchi
    (
        "armourRhoKchi",
        rho*dimensionedScalar("K", inv(dimTime), penalty_)*chi_
    );
    eqn -= fvm::Sp(rhoKchi, U);
    eqn += rhoKchi*UBody_;
}


bool Foam::fv::armourCoupling::read(const dictionary& dict)
{
    if (option::read(dict))
    {
        coeffs_.readIfPresent("penalty", penalty_);
        return true;
    }
    return false;
}


// ************************************************************************* //
