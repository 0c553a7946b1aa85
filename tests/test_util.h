// Small helpers shared by the test suites.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace patina::test {

/// Run `f` and return the message of the exception of type E it throws, or
/// "(no exception)" (which no assertion on a message part will match).
template <class E = std::exception, class F>
std::string message_of(F&& f)
{
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    return "(no exception)";
}

/// The exit status of `command` run by the shell (-1 when it did not exit normally).
inline int shell_status(const std::string& command)
{
    const int rc = std::system(command.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/// The whole content of `file` ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& file)
{
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace patina::test
