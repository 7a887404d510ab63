// An output directory that appears whole or not at all.
//
// Description
//     Files are written into a sibling staging directory; commit() renames it
//     to the requested path (replacing an older result). If the command fails
//     before commit(), the staging directory is removed, so no half-written
//     results are ever left behind.
#pragma once

#include <filesystem>
#include <string>

namespace armour {

class StagedOutput {
  public:
    explicit StagedOutput(const std::filesystem::path &target);
    ~StagedOutput();
    StagedOutput(const StagedOutput &) = delete;
    StagedOutput &operator=(const StagedOutput &) = delete;

    const std::filesystem::path &dir() const { return staging_; }   // write here
    const std::filesystem::path &target() const { return target_; } // final place
    std::filesystem::path file(const std::string &name) const { return staging_ / name; }
    void commit();

  private:
    std::filesystem::path target_;
    std::filesystem::path staging_;
    bool committed_ = false;
};

// Writes text to path through a temporary file and a rename.
void write_text_file(const std::filesystem::path &path, const std::string &text);

} // namespace armour
