/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourCoupling.H"
#include "armourCheckpoint.H"
#include "armourExchange.H"
#include "armourForceDensity.H"
#include "armourInterior.H"
#include "armourRecording.H"

#include "addToRunTimeSelectionTable.H"
#include "fvMatrices.H"
#include "fvMesh.H"
#include "fvmSup.H"
#include "uniformDimensionedFields.H"

// The armour side: plain C++ and Eigen, no OpenFOAM type crosses these.
#include "scene.h"
#include "scene_setup.h"

#include <chrono>
#include <csignal>
#include <exception>

#include <sys/prctl.h>
#include <unistd.h>

// * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * * //

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(armourCoupling, 0);
    addToRunTimeSelectionTable(option, armourCoupling, dictionary);
}
}


namespace
{
    //- Bodies whose loads the log lists each step
    const std::size_t maxLoggedBodies = 10;

    //- A rank ends when the program that launched it (mpirun, orted,
    //  slurmstepd) ends. mpirun passes on the signals it receives, but
    //  killed with -9 (with `armour run`'s whole group) it cannot, and the
    //  ranks, which talk to each other and not to it, would run the whole
    //  simulation on in the background, writing into a folder no command
    //  holds. A serial solver is left alone: started by hand under nohup,
    //  it must outlive its shell (`armour run` sets its own solver's).
    void endWithLauncher()
    {
        const pid_t launcher = ::getppid();
        if (::prctl(PR_SET_PDEATHSIG, SIGTERM) != 0)
        {
            WarningInFunction
                << "armour: cannot tie this rank to its launcher: it would"
                << " outlive a killed mpirun" << Foam::endl;
        }
        else if (::getppid() != launcher)
        {
            ::raise(SIGTERM); // it ended before the tie was made
        }
    }
}


// * * * * * * * * * * * * * * * * armour side  * * * * * * * * * * * * * * //

struct Foam::fv::armourCoupling::armourSide
{
    std::unique_ptr<armourFoam::bodyExchange> bodies;
    armourFoam::forceDensity density;
    std::unique_ptr<armourFoam::recording> recording;
    armourFoam::couplingTimes times;
    std::unique_ptr<armourFoam::checkpointing> checkpoints;
    //- Keep the interior of units piercing the surface in the outside's
    //  phase (armourInterior.H): the scene's fluid.mirror_interior
    bool mirrorInterior = false;
};


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
    penalty_(0),
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
    if (Pstream::parRun())
    {
        endWithLauncher();
    }
    fieldNames_ = wordList(1, "U");
    applied_.setSize(fieldNames_.size(), false);

    const fileName scenePath(sceneFile());
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
        engineName = scene.engine;
        start(scene, scenePath);
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "armour: " << err.what() << exit(FatalError);
    }

    Info<< "    armourCoupling: scene " << scenePath << ", "
        << armour_->bodies->names().size() << " bodies, engine "
        << engineName << ", K = " << penalty_ << " 1/s"
        << (armour_->times.frozen ? ", frozen (mask only)" : "") << endl;
    if (log && std::size_t(armour_->bodies->names().size()) > maxLoggedBodies)
    {
        Info<< "    armourCoupling: more than " << maxLoggedBodies
            << " bodies: no per-step load lines in this log (bodies.h5 holds"
            << " every body's loads)" << endl;
    }
}


Foam::fileName Foam::fv::armourCoupling::sceneFile() const
{
    if (!coeffs_.found("scene"))
    {
        FatalIOErrorInFunction(coeffs_)
            << "armourCouplingCoeffs needs 'scene' (an armour scene file with"
            << " a [fluid] table; `armour run` writes it)" << exit(FatalIOError);
    }
    fileName scenePath(coeffs_.get<fileName>("scene"));
    scenePath.expand();
    if (!scenePath.isAbsolute())
    {
        scenePath = mesh_.time().globalPath()/scenePath;
    }
    return scenePath;
}


void Foam::fv::armourCoupling::start
(
    const armour::Scene& scene,
    const fileName& scenePath
)
{
    const Time& runTime = mesh_.time();
    penalty_ = scene.fluid->penalty;
    armour_->mirrorInterior = scene.fluid->mirror_interior;
    armour_->times.frozen = scene.fluid->frozen;

    // The fluid and the engine must feel the same gravity.
    const Eigen::Vector3d gravity = armourFoam::toEigen
    (
        runTime.lookupObject<uniformDimensionedVectorField>("g").value()
    );
    if ((gravity - scene.gravity).norm() > 1e-9*scene.gravity.norm())
    {
        FatalIOErrorInFunction(coeffs_)
            << "constant/g " << armourFoam::toFoam(gravity)
            << " differs from the scene's run.gravity "
            << armourFoam::toFoam(scene.gravity) << exit(FatalIOError);
    }

    const fileName cache =
        coeffs_.lookupOrDefault<fileName>
        (
            "cache",
            fileName(armour::default_cache_dir())
        );
    armour_->bodies.reset
    (
        new armourFoam::bodyExchange(scene, cache, mesh_, gravity)
    );
    updateFields();

    armour_->recording.reset
    (
        new armourFoam::recording(runTime, scene.output_interval)
    );
    // The record sits beside the scene it ran (the run's output folder),
    // unless the dictionary names another folder.
    const fileName outDir =
        coeffs_.lookupOrDefault<fileName>("output", scenePath.path());
    armour_->checkpoints.reset
    (
        new armourFoam::checkpointing
        (
            outDir,
            scene.checkpoint_interval,
            runTime.value()
        )
    );
    const bool resumed = armour_->checkpoints->resumed();
    if (resumed)
    {
        armour_->checkpoints->loadInto
        (
            *armour_->bodies,
            *armour_->recording,
            armour_->times
        );
        updateFields();
        Info<< "    armourCoupling: resumed at t = " << runTime.value()
            << " s from " << armour_->checkpoints->resumedFrom().dir.string()
            << endl;
    }
    if (Pstream::master())
    {
        openRecords(scene, outDir, resumed);
    }
}


void Foam::fv::armourCoupling::openRecords
(
    const armour::Scene& scene,
    const fileName& outDir,
    bool resumed
)
{
    const Time& runTime = mesh_.time();
    if (resumed)
    {
        armour_->recording->resume
        (
            outDir,
            *armour_->bodies,
            armour_->checkpoints->resumedFrom().records,
            runTime.value()
        );
    }
    else
    {
        armour_->recording->open
        (
            outDir,
            scene.name,
            *armour_->bodies,
            runTime.value(),
            scene.checkpoint_interval <= 0
        );
    }
    if (coeffs_.found("csv"))
    {
        armour_->recording->openCsv
        (
            runTime.globalPath()/coeffs_.get<fileName>("csv"),
            resumed ? runTime.value() : -1
        );
    }
}


Foam::fv::armourCoupling::~armourCoupling()
{}


// * * * * * * * * * * * * * * * Private Functions * * * * * * * * * * * * * //

void Foam::fv::armourCoupling::updateFields()
{
    const armour::CellMask& mask = armour_->bodies->updateMask();
    scalarField& chi = chi_.primitiveFieldRef();
    vectorField& Ub = UBody_.primitiveFieldRef();
    forAll(chi, i)
    {
        chi[i] = mask.chi[i];
        Ub[i] = armourFoam::toFoam(mask.velocity[i]);
    }
    chi_.correctBoundaryConditions();
    UBody_.correctBoundaryConditions();
}


void Foam::fv::armourCoupling::mirrorInterior()
{
    // alpha changes between this step's alpha solve and the next: the next
    // solve advects it and sets rho from it; rho stays as solved here.
    if (!mesh_.foundObject<volScalarField>("alpha.water"))
    {
        return;
    }
    const vector g =
        mesh_.time().lookupObject<uniformDimensionedVectorField>("g").value();
    armourFoam::mirrorInterior
    (
        mesh_,
        armour_->bodies->body(),
        chi_.primitiveField(),
        armour_->bodies->names().size(),
        -g/mag(g),
        const_cast<volScalarField&>
        (
            mesh_.lookupObject<volScalarField>("alpha.water")
        )
    );
}


void Foam::fv::armourCoupling::couple
(
    const volScalarField& rho,
    const volVectorField& U
)
{
    ++armour_->times.steps;
    const armourFoam::stepLoads loads = exchange(rho, U);
    record(loads);
    checkpoint();
    logLoads(loads);
}


armourFoam::stepLoads Foam::fv::armourCoupling::exchange
(
    const volScalarField& rho,
    const volVectorField& U
)
{
    armourFoam::bodyExchange& bodies = *armour_->bodies;
    // Frozen (the fluid.frozen benchmark reference): units held, the mask
    // imposed once, no loads and no engine step.
    if (armour_->times.frozen)
    {
        return armourFoam::stepLoads::zero(bodies.names().size());
    }

    using clock = std::chrono::steady_clock;
    const auto seconds = [](clock::time_point a, clock::time_point b)
    {
        return std::chrono::duration<double>(b - a).count();
    };
    armourFoam::couplingTimes& times = armour_->times;
    try
    {
        const clock::time_point t0 = clock::now();
        // Loads from the fields at the start of the step, with the mask they
        // were computed with.
        armourFoam::stepLoads loads = bodies.sumLoads
        (
            armour_->density.compute(mesh_, rho, U, bodies.body()),
            rho,
            U,
            chi_,
            UBody_,
            penalty_
        );
        const clock::time_point t1 = clock::now();
        bodies.advance(loads.loads, mesh_.time().deltaTValue());
        const clock::time_point t2 = clock::now();
        updateFields();
        if (armour_->mirrorInterior)
        {
            mirrorInterior();
        }
        times.loadSeconds += seconds(t0, t1);
        times.demSeconds += seconds(t1, t2);
        times.maskSeconds += seconds(t2, clock::now());
        return loads;
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
    }
    return armourFoam::stepLoads::zero(bodies.names().size()); // not reached
}


void Foam::fv::armourCoupling::record(const armourFoam::stepLoads& loads)
{
    armourFoam::bodyExchange& bodies = *armour_->bodies;
    const Time& runTime = mesh_.time();
    const double t = runTime.value();
    if (armour_->recording->due(runTime))
    {
        const armourFoam::waterVolumes water =
            armourFoam::recording::water(mesh_, chi_);
        if (Pstream::parRun())
        {
            bodies.checkReplicas(t);
        }
        try
        {
            armour_->recording->record(t, bodies, loads, water, armour_->times);
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
        }
    }
    armour_->recording->csvRow(t, bodies, loads);
}


void Foam::fv::armourCoupling::checkpoint()
{
    try
    {
        // The checkpoint asks OpenFOAM for a one-shot write of the fields
        // (Time::writeOnce), which the option's const view of Time hides.
        const bool saved = armour_->checkpoints->step
        (
            const_cast<Time&>(mesh_.time()),
            *armour_->bodies,
            *armour_->recording,
            armour_->times
        );
        if (saved)
        {
            keepRestartPoint();
        }
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
    }
}


void Foam::fv::armourCoupling::logLoads
(
    const armourFoam::stepLoads& loads
) const
{
    // A layer of 100 units would write ~18 kB of log a step: 16 GB in a
    // 1000-wave run at the stability scene's 1.5 ms step. bodies.h5 holds
    // every body's loads.
    const armourFoam::bodyExchange& bodies = *armour_->bodies;
    if (log && std::size_t(bodies.names().size()) <= maxLoggedBodies)
    {
        forAll(bodies.names(), k)
        {
            Info<< "    armour " << bodies.names()[k]
                << ": F = " << armourFoam::toFoam(loads.loads.force[k])
                << " N, S = " << armourFoam::toFoam(loads.source[k])
                << " N" << endl;
        }
    }
}


void Foam::fv::armourCoupling::keepRestartPoint()
{
    // A run resumed from this checkpoint computes every unit's fractions
    // at its pose; the fractions kept for units at rest (from an earlier
    // pose) go here too, so both take this step on with the same mask.
    armour_->bodies->restartPoint();
    updateFields();
    // interFoam's density: set from alpha after the alpha solve, and not
    // written; a restart sets it from the alpha read, which the interior
    // mirror changed since (armourInterior.H). Written into the time folder
    // of the checkpoint, it is read back (interFoam reads rho if present).
    if (mesh_.foundObject<volScalarField>("rho"))
    {
        mesh_.lookupObject<volScalarField>("rho").write();
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
