// Rigid-body trajectories written as HDF5 plus an XDMF index for ParaView.
//
// Description
//     One HDF5 file per run, SI units, every dataset carrying "units" and
//     "description" string attributes:
//         /time                        (steps)            s
//         /bodies/id, /bodies/unit     (n)                -
//         /bodies/position             (steps, n, 3)      m, centre of mass
//         /bodies/orientation          (steps, n, 4)      -, quaternion w x y z, unit frame -> world
//         /bodies/velocity             (steps, n, 3)      m/s
//         /bodies/angular_velocity     (steps, n, 3)      rad/s, world frame
//         /bodies/external_force       (steps, n, 3)      N
//         /bodies/external_torque      (steps, n, 3)      N m
//         /bodies/contact_force        (steps, n, 3)      N
//         /units/<k>/vertices, /triangles                  exact unit shape (m), attribute "name"
//         /shapes/points               (steps, V, 3)      m, float32, every body's shape posed
//         /shapes/triangles            (T, 3)             -, connectivity into /shapes/points
//         /shapes/triangle_body, /shapes/triangle_unit (T)  -, per-triangle body and unit
//     The XDMF file beside it is a temporal collection of triangle grids, one
//     per step, each reading its row of /shapes/points through an Xdmf3
//     hyperslab ("file:/dataset|start:stride:count:extent"). Open it in
//     ParaView with an Xdmf3 reader; the legacy "XDMF Reader" does not know
//     that form. Both files are brought to a consistent state on disk after
//     every append, so a killed run keeps every completed step.
//
//     The writer keeps HDF5's default file lock while the file is open, which
//     stops a second run from truncating it. To look at a running case, open
//     it read-only with locking off (HDF5_USE_FILE_LOCKING=FALSE in the
//     reader's environment, or H5Pset_file_locking).
//
// Usage
//     BodyRecorder rec("run.h5", "run.xdmf", units, body_unit, {{"scene", "tank"}, {"dt", "1e-4"}});
//     rec.append(engine->time(), states);   // once per output step
//     rec.close();
//     auto again = BodyRecorder::reopen("run.h5", "run.xdmf", units, body_unit, 120);  // resume after step
//     120
#pragma once

#include "mesh.h"
#include "rigid_body_engine.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace armour {

struct RecorderUnit {
    std::string name;
    TriangleMesh mesh; // exact shape in the unit frame (m)
};

class BodyRecorder {
  public:
    // Creates `h5_path` (truncating) and `xdmf_path`. body_unit[i] is the
    // index in `units` of body i. `attributes` become root string attributes
    // (scene name, engine, dt, ...), next to "units_system" = "SI".
    // `compress` false (a run with checkpoints): chunks keep a fixed size, so
    // an append never moves the chunk holding earlier steps; a compressed
    // chunk grows, is rewritten elsewhere and its old space reused, and a
    // run killed then may leave the index pointing at overwritten space
    // (measured: steps before the checkpoint read back wrong after kill -9).
    // Throws InputError("PATH: reason") on any failure.
    BodyRecorder(const std::string &h5_path, const std::string &xdmf_path,
                 const std::vector<RecorderUnit> &units, const std::vector<int> &body_unit,
                 const std::vector<std::pair<std::string, std::string>> &attributes, bool compress = true);
    // Reopens an earlier `h5_path` of the same bodies for appending, keeping
    // its first `keep_steps` steps (a resumed run writes the later ones
    // again), and rewrites `xdmf_path` for them.
    static std::unique_ptr<BodyRecorder> reopen(const std::string &h5_path, const std::string &xdmf_path,
                                                const std::vector<RecorderUnit> &units,
                                                const std::vector<int> &body_unit, long keep_steps);
    ~BodyRecorder(); // closes; never throws
    BodyRecorder(const BodyRecorder &) = delete;
    BodyRecorder &operator=(const BodyRecorder &) = delete;

    // One output step: states[i] is body i. Flushes the HDF5 file and
    // rewrites the XDMF index before returning.
    void append(double time, const std::vector<BodyState> &states);

    // Idempotent. Appending after close throws InputError.
    void close();

    long steps() const;

  private:
    BodyRecorder() = default;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace armour
