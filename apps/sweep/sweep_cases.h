// The cases of a sweep: the product of [vary], the [[case]] tables, each per
// seed, every one checked through the scene reader before anything runs.
//
// Description
//     A case is the base scene with --set overrides ([set], its values, its
//     seed) applied and resolved (scene.resolved.toml text). Its id is made of
//     the varied values, e.g. "friction-0.3_spheres-20_seed-1", so it is
//     stable when values are added and readable in a file browser. Its scene
//     hash (FNV-1a of the resolved text) tells resume whether a finished case
//     still answers the same scene. A case the scene reader refuses throws
//     InputError "SWEEP: case ID: <the reader's message>".
//
// Usage
//     const SweepPlan plan = plan_sweep(read_sweep_file(path));
//     for (const SweepCase &c : plan.cases) ... c.id, c.scene_text ...
#pragma once

#include "sweep_file.h"

#include <optional>
#include <string>
#include <vector>

namespace armour {

struct SweepCase {
    std::string id;
    std::vector<std::string> column_values; // the value of each plan column in the resolved scene
    std::optional<std::int64_t> seed;
    std::vector<std::string> overrides; // KEY=VALUE, as `armour run --set` takes them
    std::string scene_text;             // the resolved scene
    std::string scene_hash;             // 16 hex digits, of the resolved scene's keys
    // The hash versions before this one took, over the text with its header
    // comment (which names the scene's absolute path): a case done under it
    // is still done when the sweep resumes from the same checkout.
    std::string earlier_scene_hash;
    // Of the scene's keys but those a resume may change (resume_key_text): a
    // case whose record has the same goes on from its run's last checkpoint
    // (a longer run.duration: more waves without running the first again).
    std::string resume_hash;
    double duration = 0.0; // s, run.duration
};

struct SweepPlan {
    SweepSpec spec;
    std::vector<std::string> columns; // the varied keys: [vary] in order, then new [[case]] keys
    std::string analysis;             // the scene's analysis kind (kSettleOnly: none, settles alone)
    std::vector<SweepCase> cases;
};

// SweepPlan::analysis of a sweep whose cases settle their layers alone
// (--settle-only): no analysis runs, the layers' figures head the tables.
inline constexpr const char *kSettleOnly = "settle";

SweepPlan plan_sweep(const SweepSpec &spec);

// FNV-1a of a resolved scene's keys: its comment lines are left out, so the
// same keys from another checkout or machine hash alike.
std::string scene_hash(const std::string &text);

// True when a case's record was written for this case's scene.
bool same_scene(const std::string &recorded_hash, const SweepCase &c);

// The value at a dotted key ("unit.0.size") of a TOML document, as plain text
// (strings unquoted); "" when absent.
std::string toml_value_at(const std::string &document, const std::string &key);

} // namespace armour
