// A guard for the regular expressions users give (--filter, --id): std::regex
// matches by backtracking, and a quantified group that holds a quantifier
// itself, "(.*)*zzz", takes time exponential in the id's length on a miss
// (a --list of one id ran past a minute). Such a pattern is refused; one
// without the outer quantifier selects the same ids.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace cavity::core {

// The first quantified group with a quantifier inside ("(.*)*", "(a+){2,}"),
// or "" where there is none. Escapes and character classes are skipped.
inline std::string nestedQuantifier(const std::string& re) {
    struct Group {
        size_t start;
        bool repeats;   // holds a quantifier
    };
    std::vector<Group> open;
    for (size_t i = 0; i < re.size(); ++i) {
        const char c = re[i];
        if (c == '\\') {
            ++i;
        } else if (c == '[') {             // a class: up to its closing ]
            size_t j = i + 1;
            if (j < re.size() && re[j] == '^') ++j;
            if (j < re.size() && re[j] == ']') ++j;
            while (j < re.size() && re[j] != ']') j += re[j] == '\\' ? 2 : 1;
            i = j;
        } else if (c == '(') {
            open.push_back({i, false});
        } else if ((c == '*' || c == '+' || c == '{') && !open.empty()) {
            open.back().repeats = true;
        } else if (c == ')' && !open.empty()) {
            const Group g = open.back();
            open.pop_back();
            const char next = i + 1 < re.size() ? re[i + 1] : '\0';
            if (g.repeats && (next == '*' || next == '+' || next == '{')) return re.substr(g.start, i + 2 - g.start);
            if (g.repeats && !open.empty()) open.back().repeats = true;
        }
    }
    return "";
}

// The longest alternative a pattern may have. std::regex parses a sequence
// by recursion, a level per term: a literal of 100,000 characters
// overflowed the stack (a segfault), and under the sanitizers one of 16,000.
// An alternation of many ids (the list a shard runs) is shallow however long
// it is; its size is bounded by std::regex's own state limit, which throws.
inline constexpr size_t kMaxPatternLength = 1024;

// The length of the pattern's longest run between alternation bars
// (escaped bars and bars in a character class do not separate).
inline size_t longestAlternative(const std::string& re) {
    size_t longest = 0, run = 0;
    bool inClass = false;
    for (size_t i = 0; i < re.size(); ++i, ++run) {
        const char c = re[i];
        if (c == '\\') {
            ++i;
            ++run;
        } else if (inClass) {
            inClass = c != ']';
        } else if (c == '[') {
            inClass = true;
        } else if (c == '|') {
            longest = std::max(longest, run);
            run = size_t(-1);   // the bar itself is not counted
        }
    }
    return std::max(longest, run);
}

// The one-line refusal of such a pattern given with `flag` (an alternative
// too long, or a nested repeat), or "".
inline std::string nestedQuantifierError(const std::string& flag, const std::string& re) {
    if (const size_t n = longestAlternative(re); n > kMaxPatternLength)
        return flag + " '" + re.substr(0, 40) + "...' (" + std::to_string(re.size()) + " characters): an alternative of " +
               std::to_string(n) + " characters, longer than the " + std::to_string(kMaxPatternLength) +
               " one may have (ids joined by '|' may be as many as std::regex takes)";
    const std::string nested = nestedQuantifier(re);
    return nested.empty() ? "" : flag + " " + re + ": " + nested + " repeats a group that repeats itself, which std::regex "
                                 "takes exponential time to miss with; drop the outer repeat";
}

}  // namespace cavity::core
