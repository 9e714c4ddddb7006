// A guard for the regular expressions users give (--filter, --id): std::regex
// matches by backtracking, and a quantified group that holds a quantifier
// itself, "(.*)*zzz", takes time exponential in the id's length on a miss
// (a --list of one id ran past a minute). Such a pattern is refused; one
// without the outer quantifier selects the same ids.
#pragma once

#include <string>

namespace cavity::core {

// The first quantified group with a quantifier inside ("(.*)*", "(a+){2,}"),
// or "" where there is none. Escapes and character classes are skipped.
inline std::string nestedQuantifier(const std::string& re) {
    size_t depthStart[256] = {};           // where each open group starts
    int depth = 0;
    bool inner[256] = {};
    for (size_t i = 0; i < re.size(); ++i) {
        const char c = re[i];
        if (c == '\\') { ++i; continue; }
        if (c == '[') {                    // a class: up to its closing ]
            size_t j = i + 1;
            if (j < re.size() && re[j] == '^') ++j;
            if (j < re.size() && re[j] == ']') ++j;
            while (j < re.size() && re[j] != ']') j += re[j] == '\\' ? 2 : 1;
            i = j;
            continue;
        }
        if (c == '(' && depth < 255) {
            depthStart[++depth] = i;
            inner[depth] = false;
        } else if ((c == '*' || c == '+' || c == '{') && depth > 0) {
            inner[depth] = true;
        } else if (c == ')' && depth > 0) {
            const bool held = inner[depth];
            const size_t from = depthStart[depth];
            --depth;
            const char next = i + 1 < re.size() ? re[i + 1] : '\0';
            if (held && (next == '*' || next == '+' || next == '{')) return re.substr(from, i + 2 - from);
            if (held && depth > 0) inner[depth] = true;
        }
    }
    return "";
}

}  // namespace cavity::core
