// Echoing input in messages: every error is one line, and text from a scene, a script, a
// plugin or the command line must neither break that line nor drive the terminal.
#pragma once

#include <cstdio>
#include <string>

namespace patina {

/// `text` on one line: control characters (newlines, terminal escape codes) become `\n`,
/// `\x1b`, ...; echoed input cannot break the one-line rule or drive the terminal.
inline std::string one_line(const std::string& text)
{
    std::string out;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n')
            out += "\\n";
        else if (c == '\t')
            out += "\\t";
        else if (u < 0x20 || u == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", u);
            out += hex;
        } else
            out += c;
    }
    return out;
}

}  // namespace patina
