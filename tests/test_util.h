// Small helpers shared by the test suites.
#pragma once

#include <exception>
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

}  // namespace patina::test
