// Text a user gave, made fit for a one-line message: every error is one
// line, so a line break or a terminal escape inside a value is written as
// \xNN. Package declarations, command-line errors and the store's
// credentials share the test of what counts as a control character.
#pragma once

#include <algorithm>
#include <string>

namespace cavity {

inline bool isControlChar(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

inline bool hasControlChar(const std::string& text) { return std::any_of(text.begin(), text.end(), isControlChar); }

inline std::string printable(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (!isControlChar(c)) {
            out += c;
            continue;
        }
        out += "\\x";
        out += "0123456789abcdef"[(c >> 4) & 15];
        out += "0123456789abcdef"[c & 15];
    }
    return out;
}

}  // namespace cavity
