// A command's flags declared once: name, value syntax, help and group. The
// declaration gives --help (CLI11 formats it, on stdout) and the parse; the
// errors keep the project's contract (README "Exit codes"): one line that
// names the flag and the value, as a value (Result), never an exit here.
//
// Rules every command shares:
//  - a flag given twice is an error unless it is declared repeatable (a
//    list flag takes one comma-separated value: --samples 8,16);
//  - an empty value (--out '') and a missing one (--out at the end, or
//    followed by another --flag) are errors naming the flag;
//  - an unknown --flag is an error naming the nearest known flag (edit
//    distance), so --half and --list are "unknown flag", not "missing value";
//  - --flag VALUE and --flag=VALUE are the same; a value may start with '-'
//    (--radius -1 is then a range error, not a missing value).
#pragma once

#include "result.h"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace cavity::flags {

struct FlagSpec {
    std::string name;          // "--samples"
    std::string valueName;     // "N[,N..]"; empty: a switch that takes no value (--list)
    std::string help;
    std::string group = "Options";
    bool repeatable = false;
};

struct CommandSpec {
    std::string program;       // "cavity run": starts the usage line and every message
    std::string description;   // first lines of --help
    std::vector<FlagSpec> flags;
    std::string positional;    // "DIR...": the positional arguments' name; empty: none allowed
    std::string positionalHelp;
    std::string footer;        // after the flags (kernels and their summaries for run)
    std::vector<std::string> examples;   // command lines --help ends with, two or three
};

struct ParsedFlags {
    bool help = false;
    std::string helpText;                                    // with help: what --help prints
    std::vector<std::pair<std::string, std::string>> values;  // (flag, value) in command-line order
    std::set<std::string> switches;                          // switches given
    std::vector<std::string> positionals;
    bool has(const std::string& sw) const { return switches.count(sw) > 0; }
};

Result<ParsedFlags> parseFlags(const CommandSpec& spec, const std::vector<std::string>& argv);
// The --help text of a command: description, usage, the flags by group, the
// footer and the examples, every line within kHelpWidth columns.
constexpr size_t kHelpWidth = 100;
std::string helpText(const CommandSpec& spec);
// `text` with each line longer than `width` wrapped at spaces; continuation
// lines hang under the line's second column (two or more spaces after its
// first word, as in a table), or under its indentation.
std::string wrapText(const std::string& text, size_t width = kHelpWidth);
// The candidate nearest to `word` by edit distance, or "" when none is close.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace cavity::flags
