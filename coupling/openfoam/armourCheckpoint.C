/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourCheckpoint.H"

#include "Pstream.H"
#include "error.H"
#include "input_error.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace
{
    //- The run's wall time [s], earlier parts included: `armour run` passes
    //  its origin (s since the epoch) in ARMOUR_WALL_ORIGIN; a case run by
    //  hand has none and records 0
    double runWallSeconds()
    {
        const char* origin = std::getenv("ARMOUR_WALL_ORIGIN");
        if (!origin || !*origin)
        {
            return 0;
        }
        const double now = std::chrono::duration<double>
        (
            std::chrono::system_clock::now().time_since_epoch()
        ).count();
        return now - std::atof(origin);
    }
}

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

armourFoam::checkpointing::checkpointing
(
    const std::string& outDir,
    double interval,
    double t0
)
:
    outDir_(outDir),
    interval_(interval),
    checkpoints_(outDir, interval, t0)
{
    if (t0 <= 0)
    {
        return;
    }
    const std::optional<armour::Checkpoint> last =
        armour::last_checkpoint(outDir);
    // The case names its time folders with 17 digits when it checkpoints
    // (fluid_case/foam_restart.h), so OpenFOAM restarts at the exact time.
    if (!last || std::abs(last->time - t0) > 1e-9*std::max(1.0, t0))
    {
        FatalErrorInFunction
            << "armour: the case starts at t = " << t0 << " s but "
            << outDir << "/checkpoints holds no checkpoint of that time"
            << " (`armour run --resume` restarts a case from its last"
            << " checkpoint)" << Foam::exit(Foam::FatalError);
    }
    resume_ = last;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void armourFoam::checkpointing::loadInto
(
    bodyExchange& bodies,
    recording& rec,
    couplingTimes& times
) const
{
    const std::string dir = resume_->dir.string();
    bodies.loadState(dir);
    const armour::CouplingState c = armour::read_coupling_state(dir);
    rec.setNextRecord(c.next_record);
    times.steps = c.steps;
    times.loadSeconds = c.load_seconds;
    times.demSeconds = c.dem_seconds;
    times.maskSeconds = c.mask_seconds;
}


void armourFoam::checkpointing::commit(const Foam::Time& runTime)
{
    // The fields of pending_.time were written at the end of the last step:
    // in the case's time folder, or in processor<N>/ of a parallel run.
    const fs::path caseDir(runTime.globalPath());
    const fs::path fluid = fs::path(partial_)/"fluid";
    fs::create_directories(fluid);
    const bool parallel = Foam::Pstream::parRun();
    int copied = 0;
    if (!parallel)
    {
        fs::copy
        (
            caseDir/timeName_,
            fluid/timeName_,
            fs::copy_options::recursive
        );
        ++copied;
    }
    for (const auto& entry : fs::directory_iterator(caseDir))
    {
        const std::string name = entry.path().filename().string();
        if
        (
            parallel
         && name.rfind("processor", 0) == 0
         && fs::is_directory(entry.path()/timeName_)
        )
        {
            fs::create_directories(fluid/name);
            fs::copy
            (
                entry.path()/timeName_,
                fluid/name/timeName_,
                fs::copy_options::recursive
            );
            ++copied;
        }
    }
    if (copied != (parallel ? Foam::Pstream::nProcs() : 1))
    {
        throw armour::InputError
        (
            caseDir.string() + ": the fields of t = " + timeName_
          + " s are not all written (" + std::to_string(copied)
          + " time folders): no checkpoint"
        );
    }
    checkpoints_.commit(pending_, partial_);
    Foam::Info<< "    armourCoupling: checkpoint at t = " << pending_.time
        << " s in " << outDir_ << "/checkpoints" << Foam::endl;
}


bool armourFoam::checkpointing::step
(
    Foam::Time& runTime,
    const bodyExchange& bodies,
    const recording& rec,
    const couplingTimes& times
)
{
    if (interval_ <= 0)
    {
        return false;
    }
    const double t = runTime.value();
    const double dt = runTime.deltaTValue();
    if (phase_ == 2)
    {
        if (Foam::Pstream::master())
        {
            commit(runTime);
        }
        phase_ = 0;
    }
    if (phase_ == 1)
    {
        // Time t: the engine has advanced to it; the fields of t are
        // written at the end of this step.
        pending_.time = t;
        pending_.records = rec.records();
        pending_.wall_seconds = runWallSeconds();
        timeName_ = runTime.timeName();
        std::string dir;
        if (Foam::Pstream::master())
        {
            partial_ = checkpoints_.begin().string();
            dir = partial_;
            armour::write_coupling_state
            (
                dir,
                {
                    rec.nextRecord(),
                    times.steps,
                    times.loadSeconds,
                    times.demSeconds,
                    times.maskSeconds
                }
            );
        }
        else
        {
            dir = std::string(runTime.globalPath())
                + "/armourEngine/processor"
                + std::to_string(Foam::Pstream::myProcNo()) + "/checkpoint";
            fs::remove_all(dir);
            fs::create_directories(dir);
        }
        bodies.saveState(dir);
        phase_ = 2;
        return true;
    }
    // Two more steps must fit before the end: the run is whole then.
    if (checkpoints_.due_ahead(t, dt, runTime.endTime().value(), 2))
    {
        runTime.writeOnce();
        phase_ = 1;
        checkpoints_.started(t);
    }
    return false;
}


// ************************************************************************* //
