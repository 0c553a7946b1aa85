// The command-line edge of every Patina tool: CLI11's parse errors in the tools' one form,
// `patina-<tool>: error: <message>` on one line, exit status 2 (a usage error); --help and
// --version print as CLI11 does and exit 0.
#pragma once

#include "core/one_line.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace patina {

/// Validators with short messages ("must be > 0, got -4"), where CLI::PositiveNumber prints
/// the 309 digits of DBL_MAX as its bound. Numbers are read as doubles: NaN is refused too.
inline const CLI::Validator positive{
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !(v > 0))
            return "must be a number > 0, got '" + one_line(text) + "'";
        return {};
    },
    "> 0"};
inline const CLI::Validator non_negative{
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !(v >= 0))
            return "must be a number >= 0, got '" + one_line(text) + "'";
        return {};
    },
    ">= 0"};

/// A number option's value must be finite: "nan", "inf" and their kin are refused.
inline const CLI::Validator finite{
    [](std::string& text) -> std::string {
        double v = 0;
        if (CLI::detail::lexical_cast(text, v) && !std::isfinite(v))
            return "must be a finite number, got '" + one_line(text) + "'";
        return {};
    },
    "finite"};

/// Adds `finite` to every option of `app` and its sub-commands that takes floating-point
/// numbers (CLI11's type name FLOAT): NaN and infinities are refused by every tool, whatever
/// range checks the option has (or lacks). Call after the options are registered.
inline void refuse_non_finite_numbers(CLI::App& app)
{
    for (CLI::Option* o : app.get_options())
        if (o->get_type_name().rfind("FLOAT", 0) == 0)
            o->check(finite);
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        refuse_non_finite_numbers(*sub);
}

/// Report a CLI11 parse error of `app` for `tool` ("patina-texgen") and return the exit
/// status. An unknown sub-command is named with the list of the known ones.
inline int report_parse_error(const CLI::App& app, const CLI::ParseError& e, const char* tool,
                              int argc, char** argv)
{
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success))
        return app.exit(e);  // --help, --version
    std::string message = e.what();
    const auto subcommands = app.get_subcommands([](const CLI::App*) { return true; });
    if (!subcommands.empty() && app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
        std::string known;
        for (const CLI::App* s : subcommands)
            known += (known.empty() ? "" : ", ") + s->get_name();
        message = "unknown command '" + std::string(argv[1]) + "' (the commands are " + known + ")";
    }
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
        message.pop_back();
    std::fprintf(stderr, "%s: error: %s (see --help)\n", tool, one_line(message).c_str());
    return 2;
}

}  // namespace patina
