#include "checkpoints.h"

#include "input_error.h"
#include "rigid_body_engine.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>
#include <vector>

namespace armour {

namespace fs = std::filesystem;

namespace {

constexpr int kKept = 2;

std::optional<Checkpoint> read_checkpoint(const fs::path &dir) {
    std::ifstream in(dir / "checkpoint.json");
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (!in || !j.is_object() || !j.contains("time") || !j.contains("records"))
        return std::nullopt;
    Checkpoint c;
    c.time = j["time"].get<double>();
    c.records = j["records"].get<long>();
    c.wall_seconds = j.value("wall_seconds", 0.0);
    c.dir = dir;
    c.arithmetic = j.value("arithmetic", std::string());
    return c;
}

// Complete checkpoints, oldest first (names starting with '.' are partial).
std::vector<Checkpoint> complete(const fs::path &root) {
    std::vector<Checkpoint> found;
    std::error_code ec;
    for (const auto &entry : fs::directory_iterator(root, ec)) {
        if (!entry.is_directory() || entry.path().filename().string().front() == '.')
            continue;
        if (auto c = read_checkpoint(entry.path()))
            found.push_back(*c);
    }
    std::sort(found.begin(), found.end(),
              [](const Checkpoint &a, const Checkpoint &b) { return a.time < b.time; });
    return found;
}

} // namespace

namespace {

std::string libm_fingerprint() {
    // The arguments pass through a volatile so that the compiler cannot
    // fold the calls at build time (it would round them its own way).
    volatile double scale = 0.0123456789;
    std::uint64_t hash = 1469598103934665603ull; // FNV-1a
    const auto mix = [&hash](double r) {
        std::uint64_t bits;
        std::memcpy(&bits, &r, sizeof bits);
        hash = (hash ^ bits) * 1099511628211ull;
    };
    for (int i = 1; i <= 4096; ++i) {
        const double x = i * scale + 0.001; // 0.013 .. 50.6
        mix(std::exp(0.05 * x));
        mix(std::log(x));
        mix(std::pow(x, 0.4));
        mix(std::sin(x));
        mix(std::cos(x));
        mix(std::tan(x));
        mix(std::atan2(x, 1.7));
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
    return text;
}

} // namespace

std::string arithmetic_fingerprint() {
    static const std::string fingerprint = libm_fingerprint(); // the C library's code is picked at start-up
    return fingerprint;
}

std::string other_arithmetic_warning(const Checkpoint &c) {
    const std::string here = arithmetic_fingerprint();
    if (c.arithmetic.empty() || c.arithmetic == here)
        return "";
    return "--resume: " + c.dir.string() +
           " was written where the C library's maths rounds otherwise (another processor or C library: "
           "checkpoint.json arithmetic " +
           c.arithmetic + ", here " + here +
           "): the run goes on as another realisation of its case, not the run it would have been "
           "(docs/checkpoints.md)";
}

std::string checkpoint_name(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", t);
    return text;
}

std::optional<double> time_of_name(const std::string &name) {
    char *end = nullptr;
    errno = 0;
    const double t = std::strtod(name.c_str(), &end);
    if (name.empty() || end == name.c_str() || *end != '\0' || errno != 0)
        return std::nullopt;
    return t;
}

std::optional<Checkpoint> last_checkpoint(const fs::path &out) {
    const std::vector<Checkpoint> found = complete(out / "checkpoints");
    if (found.empty())
        return std::nullopt;
    return found.back();
}

Checkpoints::Checkpoints(const fs::path &out, double interval, double after)
    : root_(out / "checkpoints"), interval_(interval),
      next_(interval > 0.0 ? (std::floor(after / interval + 1e-9) + 1.0) * interval : HUGE_VAL) {}

fs::path Checkpoints::write(const Checkpoint &at, const std::function<void(const fs::path &)> &fill) {
    const fs::path partial = begin();
    fill(partial);
    const fs::path dir = commit(at, partial);
    started(at.time);
    return dir;
}

fs::path Checkpoints::begin() {
    std::error_code ec;
    fs::create_directories(root_, ec);
    // Partial folders are ours (a killed run's): they go.
    for (const auto &entry : fs::directory_iterator(root_, ec))
        if (entry.path().filename().string().rfind(".partial-", 0) == 0)
            fs::remove_all(entry.path(), ec);
    fs::path partial = root_ / (".partial-" + std::to_string(::getpid()));
    if (!fs::create_directories(partial / "engine", ec) || ec)
        throw InputError(partial.string() + ": cannot create the checkpoint folder: " + ec.message());
    return partial;
}

fs::path Checkpoints::commit(const Checkpoint &at, const fs::path &partial) {
    const nlohmann::json j = {{"time", at.time},
                              {"records", at.records},
                              {"wall_seconds", at.wall_seconds},
                              {"arithmetic", arithmetic_fingerprint()},
                              {"si_units", {{"time", "s"}, {"wall_seconds", "s"}}}};
    {
        std::ofstream out(partial / "checkpoint.json");
        out << j.dump(2) << "\n";
        if (!out.flush())
            throw InputError((partial / "checkpoint.json").string() + ": write failed");
    }
    step("written");
    // The newest earlier checkpoint stays (kKept - 1 of them); the others
    // go: older ones, and any of the same time or later that a killed run
    // left (a resume continues from the latest, so in practice none).
    const fs::path final_dir = root_ / checkpoint_name(at.time);
    const std::vector<Checkpoint> found = complete(root_);
    std::vector<Checkpoint> kept, doomed;
    for (auto c = found.rbegin(); c != found.rend(); ++c) {
        const bool earlier = c->time < at.time && c->dir != final_dir;
        (earlier && static_cast<int>(kept.size()) < kKept - 1 ? kept : doomed).push_back(*c);
    }
    // The doomed go BEFORE the new one is renamed into place, so a kill at
    // any point leaves at most kKept complete checkpoints, and the kept one
    // stands all along. Without an earlier one to stand meanwhile the new
    // one goes in first (a same-named one must leave before it).
    const bool new_first = kept.empty();
    for (const Checkpoint &c : doomed)
        if (!new_first || c.dir == final_dir)
            drop(c.dir);
    std::error_code ec;
    fs::rename(partial, final_dir, ec);
    if (ec)
        throw InputError(final_dir.string() + ": cannot move the checkpoint into place: " + ec.message());
    step("in place");
    if (new_first)
        for (const Checkpoint &c : doomed)
            if (c.dir != final_dir)
                drop(c.dir);
    return final_dir;
}

void Checkpoints::started(double t) {
    while (next_ <= t + 1e-9 * interval_)
        next_ += interval_;
}

// A folder goes by a rename to a partial name first (atomic: the checkpoint
// is whole or gone), then its removal, which is not atomic: a kill during it
// leaves a half folder under a name no reader takes and begin() removes.
void Checkpoints::drop(const fs::path &dir) {
    const fs::path gone =
        root_ / (".partial-drop-" + std::to_string(::getpid()) + "-" + std::to_string(drops_++));
    std::error_code ec;
    fs::rename(dir, gone, ec);
    if (ec)
        throw InputError(dir.string() + ": cannot remove the checkpoint: " + ec.message());
    step("set aside " + dir.filename().string());
    fs::remove_all(gone, ec);
    step("removed " + dir.filename().string());
}

void Checkpoints::step(const std::string &what) const {
    if (step_hook_)
        step_hook_(what);
}

void write_coupling_state(const fs::path &checkpoint_dir, const CouplingState &state) {
    write_state_values((checkpoint_dir / "coupling").string(),
                       {state.next_record, static_cast<double>(state.steps), state.load_seconds,
                        state.dem_seconds, state.mask_seconds});
}

CouplingState read_coupling_state(const fs::path &checkpoint_dir) {
    const fs::path file = checkpoint_dir / "coupling";
    const std::vector<double> v = read_state_values(file.string());
    if (v.size() != 5)
        throw InputError(file.string() + ": not a coupling state (" + std::to_string(v.size()) +
                         " values, not 5)");
    return {v[0], static_cast<long>(v[1]), v[2], v[3], v[4]};
}

} // namespace armour
