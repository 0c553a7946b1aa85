#include "farm/processes.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <spawn.h>
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

std::string run_and_capture(const std::vector<std::string>& argv)
{
    int fds[2];
    if (pipe(fds) != 0)
        throw std::runtime_error(fmt::format("pipe: {}", std::strerror(errno)));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
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
    std::string out;
    char buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) != 0;) {
        if (n < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        out.append(buffer, static_cast<size_t>(n));
    }
    close(fds[0]);
    const int status = wait_for(pid, argv[0]);
    if (status != 0)
        throw std::runtime_error(fmt::format("'{}' failed (exit status {})", argv[0], status));
    return out;
}

}  // namespace patina::farm
