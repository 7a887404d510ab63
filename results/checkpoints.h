// Checkpoints of a run in OUT/checkpoints/<time>/, for `armour run --resume`.
//
// Description
//     A checkpoint is one folder named by its simulated time (s), complete
//     or absent: it is filled as checkpoints/.partial-<pid> and renamed into
//     place once whole, its checkpoint.json written last inside it. Only the
//     last two are kept: the older goes before the new one is renamed into
//     place, and a folder goes by a rename to a .partial- name before its
//     removal, so whenever the run is killed (kill -9 included) at most two
//     complete checkpoints exist, no half folder carries a checkpoint's
//     name, and, once one was written, one at least is there to resume
//     from. What a checkpoint holds:
//         checkpoint.json  time (s), records (steps of bodies.h5 up to and
//                          including its time), wall_seconds of the run so far,
//                          arithmetic (the writer's arithmetic_fingerprint())
//         engine/          the engine's state (RigidBodyEngine::save_state)
//     and what its writer adds (a coupled run: the fluid's time folder, the
//     coupler's state; docs/checkpoints.md). Used by `armour run` (dry) and
//     by the interFoam plugin (coupled), so it knows no scene and no CLI.
//
// Usage
//     Checkpoints ck(out, scene.checkpoint_interval);
//     if (ck.due(t))
//         ck.write({t, records, wall}, [&](const fs::path &dir) { engine.save_state(dir / "engine"); });
//     std::optional<Checkpoint> last = last_checkpoint(out);   // complete ones only
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>

namespace armour {

struct Checkpoint {
    double time = 0.0;         // s, simulated
    long records = 0;          // steps of bodies.h5 up to and including this time
    double wall_seconds = 0.0; // s, wall time of the run up to it (earlier resumes included)
    std::filesystem::path dir; // where it lies (set by last_checkpoint and write)
    std::string arithmetic;    // the writer's arithmetic_fingerprint() ("" in older checkpoints)
};

// A fingerprint of this process's C library maths: exp, log, pow, sin, cos,
// tan and atan2 over 4096 fixed arguments, their bits hashed (16 hex digits).
// glibc picks their code by the processor (FMA or not) and its version, and
// two machines whose fingerprints differ run one command as two realisations
// that part from the first records (docs/validation/robustness.md). Equal
// fingerprints say only that these functions agree.
std::string arithmetic_fingerprint();

// A warning line (without "armour: warning: ") when checkpoint `c` was written
// by a process whose arithmetic differs from this one's: the resumed run
// goes on as another realisation of its case. Empty when they agree or the
// checkpoint predates the fingerprint.
std::string other_arithmetic_warning(const Checkpoint &c);

// A coupled run's own state in a checkpoint (CHECKPOINT/coupling): the
// interFoam plugin writes it, a resume of the plugin and `armour run`'s
// summary (the DEM's share of this part) read it. Its one layout is here.
struct CouplingState {
    double next_record = 0.0;  // s, the simulated time of the next bodies.h5 record
    long steps = 0;            // fluid steps so far
    double load_seconds = 0.0; // s of wall time so far: the loads on the units,
    double dem_seconds = 0.0;  // the engine's advances,
    double mask_seconds = 0.0; // the solid fractions
};
void write_coupling_state(const std::filesystem::path &checkpoint_dir, const CouplingState &state);
// InputError naming the file when it is not a coupling state.
CouplingState read_coupling_state(const std::filesystem::path &checkpoint_dir);

// The complete checkpoint with the latest time, if OUT/checkpoints holds one.
std::optional<Checkpoint> last_checkpoint(const std::filesystem::path &out);

// The folder name of a checkpoint at time t (s): 9 significant digits, so
// whole steps of 1e-4 s read as 0.1 rather than 0.10000000000000001.
std::string checkpoint_name(double t);

// The time (s) a folder's name reads as (an OpenFOAM time folder, a part of
// postProcessing/), when the whole name is one number.
std::optional<double> time_of_name(const std::string &name);

class Checkpoints {
  public:
    // interval <= 0: never due. `after`: the time already covered (a resumed
    // run), so the next one falls on the same grid of multiples of interval.
    Checkpoints(const std::filesystem::path &out, double interval, double after = 0.0);

    bool due(double t) const { return interval_ > 0.0 && t >= next_ - 1e-9 * interval_; }

    // For a writer whose checkpoint is whole `steps` steps of dt after it is
    // asked for (the interFoam plugin: 2, armourCheckpoint.H): one is due at
    // t and those steps end before `end` (s), half a step to spare, so the
    // run that ends is whole. Such a writer calls started(t) when it asks
    // (on every rank: commit() does not move the due time, write() does):
    // the next one is then due after t.
    bool due_ahead(double t, double dt, double end, int steps) const {
        return due(t) && t + (steps + 0.5) * dt < end;
    }
    void started(double t);

    // Writes the checkpoint `at`: `fill` writes the states into the folder it
    // is given (engine/ already exists), then checkpoint.json, the removal
    // of the older one(s) and the rename into place. Returns its folder.
    std::filesystem::path write(const Checkpoint &at,
                                const std::function<void(const std::filesystem::path &)> &fill);

    // The same in two parts, for a writer whose states are ready at
    // different times (the interFoam plugin: the fluid's fields one step
    // after the engine's): begin() makes the partial folder (with engine/),
    // commit() finishes it as write() does, leaving the due time to started().
    std::filesystem::path begin();
    std::filesystem::path commit(const Checkpoint &at, const std::filesystem::path &partial);

    // Tests only: called after each filesystem step of a commit, named
    // ("written", "set aside 0.1", "removed 0.1", "in place"); what a kill
    // there would leave is on disk then, and a throw stops the commit there.
    void set_step_hook(std::function<void(const std::string &)> hook) { step_hook_ = std::move(hook); }

  private:
    void drop(const std::filesystem::path &dir);
    void step(const std::string &what) const;

    std::filesystem::path root_;
    double interval_;
    double next_;
    int drops_ = 0; // folders set aside by this writer, for unique names
    std::function<void(const std::string &)> step_hook_;
};

} // namespace armour
