// Diagnostics of the patina script language: where a token is (file, line, column), the
// error a script raises ("FILE:LINE:COL: error: ...", like a compiler's), and the "did you
// mean" suggestion for a misspelt name.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace patina::texgen {

/// A position in a script: 1-based line and column (columns count characters, so a UTF-8
/// letter in a comment or string is one column). 0 means "no position".
struct SourceLocation {
    int line = 0;
    int column = 0;

    bool operator==(const SourceLocation&) const = default;
};

/// "LINE:COL", for messages that point at a second place ("the '(' at 3:24").
std::string to_string(SourceLocation location);

/// An error in a script. what() is "FILE:LINE:COL: error: MESSAGE"; the parts are kept for
/// callers that want to underline the token. The interpreter throws it too, for errors it
/// finds while running a statement, so that every script error reads the same.
class ScriptError : public std::runtime_error {
public:
    ScriptError(std::string file, SourceLocation location, const std::string& message);

    const std::string& file() const { return file_; }
    SourceLocation location() const { return location_; }
    /// The message without the "FILE:LINE:COL: error: " prefix.
    const std::string& message() const { return message_; }

private:
    std::string file_;
    SourceLocation location_;
    std::string message_;
};

/// Optimal-string-alignment edit distance (insertions, deletions, substitutions and swaps of
/// two neighbouring letters each cost 1), ignoring ASCII case.
int edit_distance(std::string_view a, std::string_view b);

/// The candidates closest to `word` by edit_distance, if that distance is at most
/// max(|word|, 3) / 3 (the bound rustc uses) and less than the longer name's length (so 'a'
/// does not suggest 't'): all candidates at the smallest distance, in the order given.
/// Empty if nothing is that close.
std::vector<std::string> closest_names(std::string_view word,
                                       std::span<const std::string> candidates);

/// " (did you mean 'a'?)", " (did you mean 'a' or 'b'?)", or "" when nothing is close.
std::string did_you_mean(std::string_view word, std::span<const std::string> candidates);

}  // namespace patina::texgen
