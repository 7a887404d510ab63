// The folder a command writes its results into (--out), safe for the user's files.
//
// Description
//     A command writes into DIR only when DIR does not exist, is an empty
//     folder, or is an earlier result of the same command. An earlier result
//     is known by its marker file DIR/.armour-output: the first line names the
//     command ("armour run"), each further line is one top-level entry the
//     command wrote, listed before the entry is created, so even a killed
//     run's marker lists what it made. Any other DIR (a working folder, the
//     folder holding the input STL, a result with a file added later) is
//     refused with one InputError before any work. Replacing an earlier
//     result removes only the entries its marker lists; DIR itself is never
//     removed or renamed, so `--out .` works and the shell's folder survives.
//
//     One command at a time: the constructor takes an flock(2) on
//     DIR/.armour-lock (creating DIR if needed) and a second command into
//     DIR is refused at once, naming the holder's pid. The kernel drops the
//     lock however the holder ends (kill -9 too); the tools a command starts
//     to write into DIR inherit it (inherit_output_locks), nothing else does
//     (MPI's start-up helper would keep DIR locked for a moment after a
//     kill). Holding it, a command removes what a killed one left
//     (.armour-partial-PID, .armour-output.tmp, the lock file itself).
//
//     Two ways of writing:
//     - staged: the result appears whole or not at all. It is staged in the
//       hidden DIR/.armour-partial-PID, whose entries then replace the listed
//       old ones one by one, summary.json last. A failure before commit()
//       leaves DIR as it was (a DIR the command created is removed again).
//     - streaming: entries are written straight into DIR as the command goes
//       (a long run that stops keeps what it wrote); open() removes the
//       earlier result's entries.
//
// Usage
//     OutputFolder out(request.out, "armour clump", OutputFolder::Mode::staged); // checks DIR
//     ... the work ...
//     out.open();
//     write_text_file(out.claim("summary.json"), text); // every top-level entry through claim()
//     out.commit();                                       // staged only
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace armour {

class OutputFolder {
  public:
    enum class Mode { staged, streaming };

    // Throws InputError when `target` may not be written by `command`, or
    // another command holds it.
    OutputFolder(const std::filesystem::path &target, std::string command, Mode mode);
    ~OutputFolder();
    OutputFolder(const OutputFolder &) = delete;
    OutputFolder &operator=(const OutputFolder &) = delete;

    // Checks the folder again and makes it writable: staged, creates the
    // staging folder; streaming, removes the earlier result's entries and
    // writes a fresh marker. Calling it again does nothing.
    void open();
    // The path of top-level entry `name`; streaming, it is listed in the
    // marker first. Needs open().
    std::filesystem::path claim(const std::string &name);
    // Staged: moves the staged entries into place and lists them in the marker.
    void commit();
    // Streaming, instead of open(): continues an earlier result of this
    // command (`armour run --resume`): its entries stay and stay listed,
    // only its summary.json goes (a result being continued is not whole).
    void resume();

    // What the constructor checks, changing nothing (`armour run --dry-run`):
    // throws the InputError it would throw for `target` (not a folder, not
    // empty and not an earlier result of `command`, in use by a live command).
    // Returns the folder, absolute.
    static std::filesystem::path check_writable(const std::filesystem::path &target,
                                                const std::string &command);

    const std::filesystem::path &target() const { return target_; } // the final place
    // Where entries are written until commit(): the staging folder, or DIR
    // when streaming (for a tool that writes its own files there; staged, all
    // it leaves is committed). Needs open().
    const std::filesystem::path &dir() const { return mode_ == Mode::staged ? staging_ : target_; }

  private:
    struct Earlier {
        bool exists = false;              // the folder exists
        std::vector<std::string> entries; // what its marker lists (empty folder: none)
    };
    Earlier check() const { return check(target_, command_); }
    static Earlier check(const std::filesystem::path &target, const std::string &command);
    void write_marker(const std::filesystem::path &dir, const std::vector<std::string> &entries) const;
    void remove_entries(const std::vector<std::string> &entries) const;
    void create_target();
    void lock();
    void release(); // what a command that did not finish leaves: only its result

    std::filesystem::path target_;
    std::string command_;
    Mode mode_;
    bool opened_ = false, committed_ = false;
    std::filesystem::path staging_;              // staged: where entries are written until commit()
    std::vector<std::string> claimed_;           // streaming: entries listed in the marker
    std::vector<std::filesystem::path> created_; // folders made for DIR, removed if left empty
    int lock_fd_ = -1;                           // DIR/.armour-lock, held until destruction
};

// In a child process between fork and exec: lets the program it becomes hold
// the output-folder locks this process holds. Only for the tools a command
// starts to write into its folder (interFoam, mpirun, a sweep's cases), so
// the folder stays locked while they may still write; other programs (MPI's
// start-up helper, a plot script) do not inherit them. Async-signal-safe.
void inherit_output_locks();

// The command whose result `dir` is, as its marker names it ("armour run");
// "" when it has no marker.
std::string result_of(const std::filesystem::path &dir);

// Writes text to path through a temporary file and a rename.
void write_text_file(const std::filesystem::path &path, const std::string &text);

// The whole file, byte for byte ("" when it cannot be read).
std::string read_text_file(const std::filesystem::path &path);

// The whole lines a growing file (a solver's log) gained since byte `offset`,
// which moves past them ("" when it cannot be read): each line read once, a
// line still being written left for the next call.
std::string read_new_lines(const std::filesystem::path &path, std::uintmax_t &offset);

} // namespace armour
