#include "farm/processes.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace patina::farm {

namespace {

    int wait_for(pid_t pid, const std::string& name)
    {
        int status = 0;
        while (waitpid(pid, &status, 0) < 0)
            if (errno != EINTR)
                throw std::runtime_error(fmt::format("waiting for {}: {}", name, std::strerror(errno)));
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }

    pid_t spawn(const std::vector<std::string>& argv, posix_spawn_file_actions_t* actions)
    {
        std::vector<char*> args;
        for (const std::string& a : argv)
            args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        pid_t pid = 0;
        const int err = posix_spawnp(&pid, args[0], actions, nullptr, args.data(), environ);
        if (err != 0)
            throw std::runtime_error(fmt::format("cannot run '{}': {}", argv[0], std::strerror(err)));
        return pid;
    }

}  // namespace

int run_program(const std::vector<std::string>& argv)
{
    return wait_for(spawn(argv, nullptr), argv.at(0));
}

namespace {

    /// Runs `argv` with stdout into a pipe read into `out` and, when `err_fd` >= 0, stderr
    /// into that file; returns the exit status.
    int run_piped(const std::vector<std::string>& argv, std::string* out, int err_fd);

}  // namespace

std::string run_and_capture(const std::vector<std::string>& argv)
{
    std::string out;
    const int status = run_piped(argv, &out, -1);
    if (status != 0)
        throw std::runtime_error(fmt::format("'{}' failed (exit status {})", argv[0], status));
    return out;
}

int run_capturing(const std::vector<std::string>& argv, std::string* out, std::string* err)
{
    // stderr into an unlinked temporary file: no pipe to fill while stdout is read.
    char name[] = "/tmp/patina-farm-stderr-XXXXXX";
    const int fd = mkstemp(name);
    if (fd < 0)
        throw std::runtime_error(fmt::format("cannot create a temporary file: {}", std::strerror(errno)));
    unlink(name);
    int status = 0;
    try {
        status = run_piped(argv, out, fd);
    } catch (...) {
        close(fd);
        throw;
    }
    err->clear();
    char buffer[4096];
    for (off_t at = 0;;) {
        const ssize_t n = pread(fd, buffer, sizeof buffer, at);
        if (n <= 0)
            break;
        err->append(buffer, static_cast<size_t>(n));
        at += n;
    }
    close(fd);
    return status;
}

namespace {

int run_piped(const std::vector<std::string>& argv, std::string* out, int err_fd)
{
    int fds[2];
    if (pipe(fds) != 0)
        throw std::runtime_error(fmt::format("pipe: {}", std::strerror(errno)));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    if (err_fd >= 0)
        posix_spawn_file_actions_adddup2(&actions, err_fd, STDERR_FILENO);
    pid_t pid = 0;
    try {
        pid = spawn(argv, &actions);
    } catch (...) {
        posix_spawn_file_actions_destroy(&actions);
        close(fds[0]);
        close(fds[1]);
        throw;
    }
    posix_spawn_file_actions_destroy(&actions);
    close(fds[1]);
    char buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) != 0;) {
        if (n < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        out->append(buffer, static_cast<size_t>(n));
    }
    close(fds[0]);
    return wait_for(pid, argv[0]);
}

}  // namespace

}  // namespace patina::farm
