// Reading a JSON file someone else wrote. Google Benchmark's JSON reporter
// prints a non-finite double as a bare NaN or Infinity (the cv aggregate of a
// counter that is always 0, such as cavity_bench's "half", is 0/0), which is
// not JSON and which nlohmann::json refuses. We read those tokens as null rather than ask
// every user to clean their files.
#pragma once

#include "result.h"

#include <nlohmann/json.hpp>

#include <string>

namespace cavity::core {

// The text with every bare NaN, Infinity or inf (any case, optionally signed)
// outside a string replaced by null. Tokens inside strings are left alone, and
// no newline is added or removed, so a parse error keeps its line number.
std::string nullNonFiniteTokens(const std::string& text);

// The parsed document, or a one-line bad-input error naming the file:
// "FILE: cannot be read (no such file)", "FILE: is a folder, not a JSON file",
// "FILE: does not parse: line L: what nlohmann::json objected to".
Result<nlohmann::json> readJsonFile(const std::string& path);

// Writes `text` to a temporary file beside `path` and renames it into place,
// so a reader (or a kill halfway) sees the old file or the new one, never a
// part. Every report and JSON file we write goes through here.
// Removes from `dir` what a killed writer left: every "NAME.tmp-PID" or
// "STEM.tmp-PID.EXT" whose process PID no longer runs. Once per folder and
// process; the atomic writers call it before they write, so the next
// command cleans up after a kill -9.
void removeStaleTemps(const std::string& dir);

Status writeFileAtomically(const std::string& path, const std::string& text);

// The document as text (indent < 0: one line). A string that is not UTF-8
// (a compile error quoting a Latin-1 byte of a user's shader, a path) is
// written with U+FFFD in place of its bad bytes instead of throwing.
inline std::string jsonText(const nlohmann::json& j, int indent = -1) {
    return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace cavity::core