// A command line as a shell reads it back: the `command` that results.json
// and a render folder's manifest record is pasted into a terminal to run
// the same thing again, so a --filter of "^a|b$" or a folder with a space
// must come back as one word.
#pragma once

#include <string>
#include <vector>

namespace cavity::core {

// `s` itself where every character is one no shell treats specially, else
// in single quotes (a quote inside as '\'').
inline std::string shellWord(const std::string& s) {
    const bool plain = !s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789_-./:=,@%+") == std::string::npos;
    if (plain) return s;
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

inline std::string commandLine(std::string program, const std::vector<std::string>& args) {
    for (const auto& a : args) {
        program += ' ';
        program += shellWord(a);
    }
    return program;
}

}  // namespace cavity::core
