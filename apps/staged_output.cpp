#include "staged_output.h"

#include "mesh.h"

#include <fstream>
#include <system_error>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;

StagedOutput::StagedOutput(const fs::path &target) : target_(fs::absolute(target).lexically_normal()) {
    if (target.empty())
        throw InputError("--out: an output directory is required");
    if (target_.filename().empty())
        target_ = target_.parent_path();
    std::error_code ec;
    if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
        throw InputError("--out: " + target_.string() + " exists and is not a directory");
    fs::create_directories(target_.parent_path(), ec);
    if (ec)
        throw InputError("--out: cannot create " + target_.parent_path().string() + ": " + ec.message());
    staging_ = target_;
    staging_ += ".partial-" + std::to_string(::getpid());
    fs::remove_all(staging_, ec);
    if (!fs::create_directory(staging_, ec) || ec)
        throw InputError("--out: cannot create " + staging_.string() + ": " + ec.message());
}

StagedOutput::~StagedOutput() {
    if (!committed_) {
        std::error_code ec;
        fs::remove_all(staging_, ec);
    }
}

void StagedOutput::commit() {
    std::error_code ec;
    fs::path old = target_;
    old += ".old-" + std::to_string(::getpid());
    const bool replacing = fs::exists(target_, ec);
    if (replacing)
        fs::rename(target_, old);
    fs::rename(staging_, target_);
    committed_ = true;
    if (replacing)
        fs::remove_all(old, ec);
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
