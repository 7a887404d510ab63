#include "output_folder.h"

#include "input_error.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <signal.h>
#include <sstream>
#include <stdexcept>
#include <sys/file.h>
#include <sys/stat.h>
#include <system_error>
#include <thread>
#include <unistd.h>
#include <utility>

namespace armour {

namespace fs = std::filesystem;

namespace {

const std::string kMarker = ".armour-output";
const std::string kLock = ".armour-lock";

// `name` is `prefix` followed by a pid (digits only).
bool prefix_and_pid(const std::string &name, const std::string &prefix) {
    return name.size() > prefix.size() && name.rfind(prefix, 0) == 0 &&
           name.find_first_not_of("0123456789", prefix.size()) == std::string::npos;
}

// Files of a command that was killed: the marker's temporary copy, a staging
// folder (.armour-partial-PID) and the lock file (its lock went with the
// process). They carry our names only, so they may go once we hold the lock.
bool own_leftover(const std::string &name) {
    return name == kMarker + ".tmp" || name == kLock || prefix_and_pid(name, ".armour-partial-");
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

bool process_alive(const std::string &pid) {
    try {
        return ::kill(static_cast<pid_t>(std::stol(pid)), 0) == 0 || errno == EPERM;
    } catch (const std::exception &) {
        return false; // out of range: no such process
    }
}

// Earlier versions staged a new DIR in the sibling DIR.partial-PID; a killed
// one left it there. Whether it is ours cannot be proven (a user may name a
// folder so), so it is named, never removed.
void warn_about_old_staging(const fs::path &target) {
    std::error_code ec;
    const std::string prefix = target.filename().string() + ".partial-";
    for (const auto &entry : fs::directory_iterator(target.parent_path(), ec)) {
        const std::string name = entry.path().filename().string();
        if (prefix_and_pid(name, prefix) && !process_alive(name.substr(prefix.size())))
            std::fprintf(stderr,
                         "armour: warning: %s looks like what a killed earlier armour left (pid %s is "
                         "gone); remove it by hand if it is\n",
                         entry.path().c_str(), name.substr(prefix.size()).c_str());
    }
}

// The folder `--out` names, absolute; "dir/" and "." name the folder itself.
fs::path normalised_target(const fs::path &target) {
    if (target.empty())
        throw InputError("--out: an output directory is required");
    const fs::path folder = fs::absolute(target).lexically_normal();
    return folder.filename().empty() ? folder.parent_path() : folder;
}

InputError in_use_error(const fs::path &target, const std::string &holder) {
    return InputError("--out " + target.string() + ": in use by another armour command (pid " +
                      (holder.empty() ? "unknown" : holder) +
                      "); wait for it to end or choose another folder");
}

// The lock descriptors this process holds (-1: a free slot). A plain array:
// inherit_output_locks() reads it in a forked child, where nothing may
// allocate.
constexpr std::size_t kMaxLocks = 16;
std::array<int, kMaxLocks> held_locks = [] {
    std::array<int, kMaxLocks> slots{};
    slots.fill(-1);
    return slots;
}();

void remember_lock(int fd, bool held) {
    for (int &slot : held_locks)
        if (slot == (held ? -1 : fd)) {
            slot = held ? fd : -1;
            return;
        }
}

} // namespace

void inherit_output_locks() {
    for (const int fd : held_locks)
        if (fd >= 0) {
            const int flags = ::fcntl(fd, F_GETFD);
            if (flags >= 0)
                ::fcntl(fd, F_SETFD, flags & ~FD_CLOEXEC);
        }
}

OutputFolder::OutputFolder(const fs::path &target, std::string command, Mode mode)
    : target_(normalised_target(target)), command_(std::move(command)), mode_(mode) {
    check(); // a folder that is not ours is refused untouched
    try {
        create_target();
        lock();
        check(); // again: the holder before us may have changed it
    } catch (...) {
        release();
        throw;
    }
    warn_about_old_staging(target_);
}

OutputFolder::~OutputFolder() {
    release();
}

void OutputFolder::create_target() {
    if (fs::exists(target_))
        return;
    std::vector<fs::path> missing;
    for (fs::path p = target_; !p.empty() && !fs::exists(p); p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path())
            break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        std::error_code ec;
        if (!fs::create_directory(*it, ec) && !fs::is_directory(*it))
            throw InputError("--out " + target_.string() + ": cannot create " + it->string() + ": " +
                             (ec ? ec.message() : "exists"));
        if (!ec)
            created_.push_back(*it);
    }
}

// flock(2) on DIR/.armour-lock: the kernel drops the lock when the last
// process holding it ends, however it ends (kill -9 too). The descriptor is
// inherited only by the tools a command starts to write into the folder
// (inherit_output_locks: interFoam, mpirun, a sweep's cases), so it stays
// locked while they may still write into it. MPI's start-up helper (orted,
// which LIGGGHTS' MPI_Init starts) held it too, for a moment after a kill -9:
// a resume started then was refused as in use.
void OutputFolder::lock() {
    const fs::path file = target_ / kLock;
    const auto patience = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    for (;;) {
        const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0)
            throw InputError("--out " + target_.string() + ": cannot create " + kLock + ": " +
                             std::strerror(errno));
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int error = errno;
            if (error != EWOULDBLOCK) {
                // A file system without locks (some network mounts) still works, unguarded.
                std::fprintf(stderr,
                             "armour: warning: --out %s: cannot lock %s (%s); a second command into it "
                             "would not be refused\n",
                             target_.c_str(), kLock.c_str(), std::strerror(error));
                lock_fd_ = fd;
                remember_lock(fd, true);
                return;
            }
            char text[32] = {};
            const ssize_t got = ::pread(fd, text, sizeof text - 1, 0);
            ::close(fd);
            std::string holder(text, got > 0 ? static_cast<std::size_t>(got) : 0);
            holder.erase(std::min(holder.size(), holder.find_first_not_of("0123456789"))); // the pid only
            // A command killed with -9 leaves what it started holding the lock
            // for a moment (MPI's orted daemon ends within milliseconds of its
            // parent): give those a few seconds rather than refuse at once.
            const bool holder_ended =
                !holder.empty() && ::kill(static_cast<pid_t>(std::stol(holder)), 0) != 0 && errno == ESRCH;
            if (holder_ended && std::chrono::steady_clock::now() < patience) {
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
                continue;
            }
            if (holder_ended)
                throw InputError(
                    "--out " + target_.string() + ": in use by a program the ended armour command " + holder +
                    " started (interFoam or mpirun still running?); end it or choose " + "another folder");
            throw in_use_error(target_, holder);
        }
        // The holder before us removes the file as it lets go: a lock taken on
        // the removed file guards nothing, so open the new one.
        struct stat held = {};
        struct stat named = {};
        if (::fstat(fd, &held) == 0 && ::stat(file.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
            held.st_dev == named.st_dev) {
            const std::string pid = pid_suffix() + "\n";
            if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
                // The pid is only for the refusal's message.
            }
            lock_fd_ = fd;
            remember_lock(fd, true);
            return;
        }
        ::close(fd);
    }
}

void OutputFolder::release() {
    std::error_code ec;
    if (mode_ == Mode::staged && opened_ && !committed_)
        fs::remove_all(staging_, ec);
    if (lock_fd_ >= 0) {
        fs::remove(target_ / kLock, ec); // before letting go: see lock()
        remember_lock(lock_fd_, false);
        ::close(lock_fd_);
        lock_fd_ = -1;
    }
    // Folders this command created and left empty (it failed before writing).
    for (auto it = created_.rbegin(); it != created_.rend(); ++it)
        if (!fs::remove(*it, ec))
            break;
    created_.clear();
}

fs::path OutputFolder::check_writable(const fs::path &target, const std::string &command) {
    const fs::path folder = normalised_target(target);
    check(folder, command);
    // A folder to be made: its nearest existing parent must take it.
    fs::path parent = folder;
    while (!fs::exists(parent) && parent != parent.parent_path())
        parent = parent.parent_path();
    if (parent != folder && (!fs::is_directory(parent) || ::access(parent.c_str(), W_OK) != 0))
        throw InputError("--out " + folder.string() + ": cannot create it in " + parent.string() + ": " +
                         (fs::is_directory(parent) ? std::strerror(errno) : "not a folder"));
    // The lock's holder, as lock() would find it, without taking the lock:
    // a lock file left by a killed command names a pid that is gone.
    std::ifstream lock_file(folder / kLock);
    std::string holder;
    if (lock_file && std::getline(lock_file, holder) && !holder.empty() &&
        holder.find_first_not_of("0123456789") == std::string::npos && process_alive(holder))
        throw in_use_error(folder, holder);
    return folder;
}

OutputFolder::Earlier OutputFolder::check(const fs::path &target, const std::string &command) {
    Earlier earlier;
    std::error_code ec;
    const fs::file_status status = fs::status(target, ec);
    if (!fs::exists(status))
        return earlier;
    if (!fs::is_directory(status))
        throw InputError("--out " + target.string() + ": exists and is not a folder");
    earlier.exists = true;
    std::string owner;
    std::ifstream marker(target / kMarker);
    const bool marked = static_cast<bool>(marker);
    if (marked && std::getline(marker, owner))
        for (std::string line; std::getline(marker, line);)
            if (plain_entry(line))
                earlier.entries.push_back(line);
    const std::string refused =
        "--out " + target.string() + ": not empty and not an earlier result of '" + command + "' (";
    const std::string advice = "); choose a new or empty folder";
    if (marked && owner != command)
        throw InputError(refused + "it is a result of '" + owner + "'" + advice);
    for (const std::string &name : entries_of(target))
        if (std::find(earlier.entries.begin(), earlier.entries.end(), name) == earlier.entries.end() &&
            !temporary_of(name, earlier.entries))
            throw InputError(refused + "holds '" + name + "'" + advice);
    return earlier;
}

std::string result_of(const fs::path &dir) {
    std::ifstream marker(dir / kMarker);
    std::string owner;
    std::getline(marker, owner);
    return owner;
}

void OutputFolder::open() {
    if (opened_)
        return;
    const Earlier earlier = check();
    std::error_code ec;
    // Leftovers of a killed command (checked to carry only our names; we hold
    // the lock, so no live command is writing them).
    std::vector<fs::path> leftovers;
    for (const auto &entry : fs::directory_iterator(target_, ec)) {
        const std::string name = entry.path().filename().string();
        if (own_leftover(name) && name != kLock)
            leftovers.push_back(entry.path());
    }
    for (const fs::path &path : leftovers)
        fs::remove_all(path, ec);
    if (mode_ == Mode::staged) {
        staging_ = target_ / (".armour-partial-" + pid_suffix());
        if (!fs::create_directory(staging_, ec) || ec)
            throw InputError("--out " + target_.string() + ": cannot create " + staging_.string() + ": " +
                             ec.message());
    } else {
        for (const std::string &name : earlier.entries)
            fs::remove(target_ / (name + ".tmp"), ec);
        remove_entries(earlier.entries);
        write_marker(target_, {});
        created_.clear(); // a streaming result stays, whatever happens next
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
    // Checked again (the user may have added a file while the command
    // worked); the marker lists old and new entries while they are swapped,
    // so an interrupted swap is still recognised as ours.
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
    created_.clear();
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

std::string read_text_file(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string read_new_lines(const fs::path &path, std::uintmax_t &offset) {
    std::ifstream in(path, std::ios::binary);
    if (!in.seekg(static_cast<std::streamoff>(offset)))
        return "";
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.resize(text.rfind('\n') + 1); // npos + 1 = 0: no whole line yet
    offset += text.size();
    return text;
}

} // namespace armour
