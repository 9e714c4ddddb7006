// The word a typo was meant to be, for the "did you mean ...?" of an error
// message: any layer that refuses a name can offer the nearest one it knows.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace cavity {

// Levenshtein distance: insertions, deletions and substitutions.
inline size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diag = up;
        }
    }
    return row[b.size()];
}

// The candidate nearest `word`, or "" when none is close enough to be a
// typo of it: at most a third of the word's letters apart, and at least 2.
inline std::string nearestWord(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    size_t bestDistance = std::string::npos;
    for (const auto& c : candidates) {
        const size_t d = editDistance(word, c);
        if (d < bestDistance) bestDistance = d, best = c;
    }
    return bestDistance <= std::max<size_t>(2, word.size() / 3) ? best : "";
}

}  // namespace cavity
