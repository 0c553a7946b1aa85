#include "texgen/patina/script_error.h"

#include <algorithm>
#include <cctype>

namespace patina::texgen {

std::string to_string(SourceLocation location)
{
    return std::to_string(location.line) + ":" + std::to_string(location.column);
}

ScriptError::ScriptError(std::string file, SourceLocation location, const std::string& message)
    : std::runtime_error(file + ":" + to_string(location) + ": error: " + message),
      file_(std::move(file)), location_(location), message_(message)
{
}

int edit_distance(std::string_view a, std::string_view b)
{
    const auto lower = [](char c) {
        return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    };
    // d[i][j]: distance between the first i letters of a and the first j letters of b
    // (Damerau's restricted form: a swapped pair counts once and is not edited again).
    const size_t n = a.size(), m = b.size();
    std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
    for (size_t i = 0; i <= n; ++i)
        d[i][0] = static_cast<int>(i);
    for (size_t j = 0; j <= m; ++j)
        d[0][j] = static_cast<int>(j);
    for (size_t i = 1; i <= n; ++i) {
        for (size_t j = 1; j <= m; ++j) {
            const int cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    }
    return d[n][m];
}

std::vector<std::string> closest_names(std::string_view word,
                                       std::span<const std::string> candidates)
{
    const int bound = static_cast<int>(std::max<size_t>(word.size(), 3) / 3);
    int best = bound + 1;
    std::vector<std::string> closest;
    for (const std::string& candidate : candidates) {
        const int distance = edit_distance(word, candidate);
        // A complete rewrite ('a' for 't') is no suggestion.
        const int longest = static_cast<int>(std::max(word.size(), candidate.size()));
        if (distance > best || distance >= longest)
            continue;
        if (distance < best) {
            best = distance;
            closest.clear();
        }
        if (std::find(closest.begin(), closest.end(), candidate) == closest.end())
            closest.push_back(candidate);
    }
    return closest;
}

std::string did_you_mean(std::string_view word, std::span<const std::string> candidates)
{
    const std::vector<std::string> closest = closest_names(word, candidates);
    if (closest.empty())
        return "";
    std::string text = " (did you mean ";
    for (size_t i = 0; i < closest.size(); ++i) {
        if (i > 0)
            text += i + 1 == closest.size() ? " or " : ", ";
        text += "'" + closest[i] + "'";
    }
    return text + "?)";
}

}  // namespace patina::texgen
