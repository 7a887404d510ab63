// Waits on what the tests that kill a run and resume it started: a child's
// exit, and an output folder's lock (docs/outputs.md) being let go.
#pragma once

#include <cerrno>
#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <sys/file.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace armour_test {

// The exit status of child `pid` once it ends; 128 + the signal that killed it.
inline int wait_for(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// True once nothing holds DIR/.armour-lock (or there is none): after SIGKILL,
// interFoam, which inherited the lock's descriptor, may outlive the reaped
// armour process for a moment, and a resume started then is refused as "in
// use". False if it is still held after 30 s (a process left running).
inline bool wait_unlocked(const std::filesystem::path &dir) {
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30)) {
        const int fd = ::open((dir / ".armour-lock").c_str(), O_RDWR);
        if (fd < 0)
            return true;
        const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
        ::close(fd);
        if (free)
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

} // namespace armour_test
