// LIGGGHTS 3.8 multisphere behind the RigidBodyEngine interface.
//
// Description
//     Runs LIGGGHTS in-process through its library. The LIGGGHTS input comes
//     from the readable templates in liggghts_inputs/, filled from the engine
//     settings with string variables. Bodies are inserted at their exact
//     poses; gravity and external loads are applied per body (held until
//     changed); states are returned in each unit's own frame. Everything is
//     validated before LIGGGHTS sees it, because LIGGGHTS ends the process on
//     its own errors; if it still does, its ERROR line from the log is printed.
//     Bodies and walls must be added before the first advance().
//
//     Each engine is one serial LIGGGHTS (opened on MPI_COMM_SELF): in an MPI
//     job every rank that builds one runs its own replica, as the interFoam
//     plugin wants. Rank 0 writes its files (log.liggghts, input.liggghts,
//     sphere and wall files) in settings.work_dir, rank r > 0 in
//     work_dir/processor<r>, so the replicas never share a file.
//
// Usage
//     EngineSettings settings;  settings.work_dir = "OUT/liggghts";
//     auto engine = make_liggghts_engine(settings);
//     // add_template / add_body / add_wall, then advance(span) ...
#pragma once

#include "engine_registry.h"
#include "rigid_body_engine.h"

#include <memory>

namespace armour {

std::unique_ptr<RigidBodyEngine> make_liggghts_engine(const EngineSettings &settings);

// Name, capabilities and factory for the registry.
EngineStyle liggghts_engine_style();

} // namespace armour
