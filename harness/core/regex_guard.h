// A guard for the regular expressions users give (--filter, --id): std::regex
// matches by backtracking, and a quantified group that holds a quantifier
// itself, "(.*)*zzz", takes time exponential in the id's length on a miss
// (a --list of one id ran past a minute). Such a pattern is refused; one
// without the outer quantifier selects the same ids.
#pragma once

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

// The longest pattern taken: std::regex compiles and matches by recursion,
// and a pattern of 100,000 characters overflowed the stack (a segfault);
// a pattern of ids is far shorter.
inline constexpr size_t kMaxPatternLength = 1024;

// The one-line refusal of such a pattern given with `flag` (too long, or a
// nested repeat), or "".
inline std::string nestedQuantifierError(const std::string& flag, const std::string& re) {
    if (re.size() > kMaxPatternLength)
        return flag + " '" + re.substr(0, 40) + "...' (" + std::to_string(re.size()) + " characters): longer than " +
               std::to_string(kMaxPatternLength) + " characters, the most a pattern may have";
    const std::string nested = nestedQuantifier(re);
    return nested.empty() ? "" : flag + " " + re + ": " + nested + " repeats a group that repeats itself, which std::regex "
                                 "takes exponential time to miss with; drop the outer repeat";
}

}  // namespace cavity::core
