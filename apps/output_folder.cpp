#include "output_folder.h"

#include "mesh.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>
#include <utility>

namespace armour {

namespace fs = std::filesystem;

namespace {

const std::string kMarker = ".armour-output";

// Temporary files of a command that was killed: the marker's temporary copy
// and a staging folder (.armour-partial-PID). They carry our names only, so they may go.
bool own_leftover(const std::string &name) {
    const std::string partial = ".armour-partial-";
    return name == kMarker + ".tmp" ||
           (name.size() > partial.size() && name.rfind(partial, 0) == 0 &&
            name.find_first_not_of("0123456789", partial.size()) == std::string::npos);
}

// "X.tmp" beside a listed X: the temporary copy a killed run was writing
// (write_text_file, the XDMF index), so ours.
bool temporary_of(const std::string &name, const std::vector<std::string> &listed) {
    const std::string suffix = ".tmp";
    return name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
           std::find(listed.begin(), listed.end(), name.substr(0, name.size() - suffix.size())) !=
               listed.end();
}

// A marker line names a top-level entry; anything that could reach outside
// the folder is ignored rather than removed.
bool plain_entry(const std::string &name) {
    return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos;
}

std::vector<std::string> entries_of(const fs::path &dir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto &entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name != kMarker && !own_leftover(name))
            names.push_back(name);
    }
    if (ec)
        throw InputError("--out " + dir.string() + ": cannot read the folder: " + ec.message());
    std::sort(names.begin(), names.end());
    return names;
}

// summary.json last: a folder holding it holds a whole result.
void summary_last(std::vector<std::string> &names) {
    std::stable_partition(names.begin(), names.end(),
                          [](const std::string &n) { return n != "summary.json"; });
}

std::string pid_suffix() {
    return std::to_string(::getpid());
}

} // namespace

OutputFolder::OutputFolder(const fs::path &target, std::string command, Mode mode)
    : target_(fs::absolute(target).lexically_normal()), command_(std::move(command)), mode_(mode) {
    if (target.empty())
        throw InputError("--out: an output directory is required");
    if (target_.filename().empty())
        target_ = target_.parent_path(); // "dir/" and "." name the folder itself
    check();
}

OutputFolder::~OutputFolder() {
    if (mode_ == Mode::staged && opened_ && !committed_) {
        std::error_code ec;
        fs::remove_all(staging_, ec);
    }
}

OutputFolder::Earlier OutputFolder::check() const {
    Earlier earlier;
    std::error_code ec;
    const fs::file_status status = fs::status(target_, ec);
    if (!fs::exists(status))
        return earlier;
    if (!fs::is_directory(status))
        throw InputError("--out " + target_.string() + ": exists and is not a folder");
    earlier.exists = true;
    std::string owner;
    std::ifstream marker(target_ / kMarker);
    const bool marked = static_cast<bool>(marker);
    if (marked && std::getline(marker, owner))
        for (std::string line; std::getline(marker, line);)
            if (plain_entry(line))
                earlier.entries.push_back(line);
    const std::string refused =
        "--out " + target_.string() + ": not empty and not an earlier result of '" + command_ + "' (";
    const std::string advice = "); choose a new or empty folder";
    if (marked && owner != command_)
        throw InputError(refused + "it is a result of '" + owner + "'" + advice);
    for (const std::string &name : entries_of(target_))
        if (std::find(earlier.entries.begin(), earlier.entries.end(), name) == earlier.entries.end() &&
            !temporary_of(name, earlier.entries))
            throw InputError(refused + "holds '" + name + "'" + advice);
    return earlier;
}

void OutputFolder::open() {
    if (opened_)
        return;
    const Earlier earlier = check();
    std::error_code ec;
    // Leftovers of a killed command (checked to carry only our names).
    if (earlier.exists) {
        std::vector<fs::path> leftovers;
        for (const auto &entry : fs::directory_iterator(target_, ec))
            if (own_leftover(entry.path().filename().string()))
                leftovers.push_back(entry.path());
        for (const fs::path &path : leftovers)
            fs::remove_all(path, ec);
    }
    if (mode_ == Mode::staged) {
        if (earlier.exists) {
            staging_ = target_ / (".armour-partial-" + pid_suffix());
        } else {
            fs::create_directories(target_.parent_path(), ec);
            if (ec)
                throw InputError("--out " + target_.string() + ": cannot create " +
                                 target_.parent_path().string() + ": " + ec.message());
            staging_ = target_;
            staging_ += ".partial-" + pid_suffix();
            fs::remove_all(staging_, ec);
        }
        if (!fs::create_directory(staging_, ec) || ec)
            throw InputError("--out " + target_.string() + ": cannot create " + staging_.string() + ": " +
                             ec.message());
    } else {
        for (const std::string &name : earlier.entries)
            fs::remove(target_ / (name + ".tmp"), ec);
        remove_entries(earlier.entries);
        fs::create_directories(target_, ec);
        if (ec)
            throw InputError("--out " + target_.string() + ": cannot create the folder: " + ec.message());
        write_marker(target_, {});
    }
    opened_ = true;
}

fs::path OutputFolder::claim(const std::string &name) {
    if (!opened_ || !plain_entry(name))
        throw std::logic_error("OutputFolder::claim('" + name + "') before open() or not a top-level name");
    if (mode_ == Mode::staged)
        return staging_ / name;
    if (std::find(claimed_.begin(), claimed_.end(), name) == claimed_.end()) {
        claimed_.push_back(name);
        write_marker(target_, claimed_);
    }
    return target_ / name;
}

void OutputFolder::commit() {
    if (mode_ != Mode::staged || !opened_ || committed_)
        return;
    std::vector<std::string> made = entries_of(staging_);
    summary_last(made);
    std::error_code ec;
    if (staging_.parent_path() != target_) {
        // A new folder: it appears whole, with its marker.
        write_marker(staging_, made);
        fs::rename(staging_, target_, ec);
        if (ec)
            throw InputError("--out " + target_.string() +
                             ": cannot move the result into place: " + ec.message());
        committed_ = true;
        return;
    }
    // An existing folder: checked again (the user may have added a file while
    // the command worked); its marker lists old and new entries while they
    // are swapped, so an interrupted swap is still recognised as ours.
    const Earlier earlier = check();
    std::vector<std::string> both = earlier.entries;
    for (const std::string &name : made)
        if (std::find(both.begin(), both.end(), name) == both.end())
            both.push_back(name);
    write_marker(target_, both);
    remove_entries(earlier.entries);
    for (const std::string &name : made) {
        fs::rename(staging_ / name, target_ / name, ec);
        if (ec)
            throw InputError("--out " + target_.string() + ": cannot move '" + name +
                             "' into place: " + ec.message());
    }
    write_marker(target_, made);
    committed_ = true;
    fs::remove_all(staging_, ec);
}

void OutputFolder::resume() {
    if (opened_)
        return;
    if (mode_ != Mode::streaming)
        throw std::logic_error("OutputFolder::resume() of a staged folder");
    const Earlier earlier = check();
    if (!earlier.exists || earlier.entries.empty())
        throw InputError("--resume: " + target_.string() + " holds no earlier result of '" + command_ +
                         "' to continue");
    claimed_ = earlier.entries;
    std::error_code ec;
    for (const std::string &name : earlier.entries)
        fs::remove(target_ / (name + ".tmp"), ec);
    remove_entries({"summary.json"});
    write_marker(target_, claimed_);
    opened_ = true;
}

void OutputFolder::write_marker(const fs::path &dir, const std::vector<std::string> &entries) const {
    std::string text = command_ + "\n";
    for (const std::string &name : entries)
        text += name + "\n";
    write_text_file(dir / kMarker, text);
}

void OutputFolder::remove_entries(const std::vector<std::string> &entries) const {
    std::vector<std::string> order = entries;
    // summary.json first: a folder without it is visibly not a whole result.
    std::stable_partition(order.begin(), order.end(),
                          [](const std::string &n) { return n == "summary.json"; });
    for (const std::string &name : order) {
        std::error_code ec;
        fs::remove_all(target_ / name, ec);
        if (ec)
            throw InputError("--out " + target_.string() + ": cannot remove the earlier '" + name +
                             "': " + ec.message());
    }
}

void write_text_file(const fs::path &path, const std::string &text) {
    fs::path temporary = path;
    temporary += ".tmp";
    {
        std::ofstream out(temporary);
        out << text;
        if (!out.flush())
            throw InputError(path.string() + ": write failed");
    }
    fs::rename(temporary, path);
}

} // namespace armour
