// Starts, and waits on, what the tests that stop a run or a sweep start: a
// child's exit, a condition on its files, and an output folder's lock
// (docs/outputs.md) being let go.
#pragma once

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <functional>
#include <string>
#include <sys/file.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace armour_test {

// Runs program `argv[0]` with `argv` in a child process, its stderr to
// /dev/null (a progress line the test does not read); returns the child's pid.
inline pid_t start_quietly(const std::vector<std::string> &argv) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::freopen("/dev/null", "w", stderr);
        std::vector<char *> args;
        for (const std::string &a : argv)
            args.push_back(const_cast<char *>(a.c_str()));
        args.push_back(nullptr);
        ::execv(args[0], args.data());
        ::_exit(127);
    }
    return pid;
}

// The exit status of child `pid` once it ends; 128 + the signal that killed it.
inline int wait_for(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Waits until `ready` holds or process `pid` ends, however slow the machine
// (no time limit: a run that hangs is left to ctest's timeout). True while
// it still runs; false when it ended first (then reaped).
inline bool wait_until(pid_t pid, const std::function<bool()> &ready) {
    int status = 0;
    while (!ready()) {
        if (::waitpid(pid, &status, WNOHANG) != 0)
            return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return true;
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
