// CLI11 declares the options, formats --help and does the parse; a pass over
// the words before it holds the project's error contract (flags.h), which
// CLI11 alone words differently ("1 required TEXT missing") or lacks (a flag
// given twice, an empty value, the nearest known flag).
#include "flags.h"

#include "nearest.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <memory>

namespace cavity::flags {

namespace {

const FlagSpec* findFlag(const CommandSpec& spec, const std::string& name) {
    for (const auto& f : spec.flags)
        if (f.name == name) return &f;
    return nullptr;
}

// The declaration as a CLI11 app writing into `values` (one vector per
// value flag) and `positionals`.
std::unique_ptr<CLI::App> makeApp(const CommandSpec& spec, std::map<std::string, std::vector<std::string>>& values,
                                  std::vector<std::string>& positionals) {
    auto app = std::make_unique<CLI::App>(spec.description, spec.program);
    app->set_help_flag("-h,--help", "print this help on stdout and exit 0");
    app->footer(spec.footer);
    for (const auto& f : spec.flags) {
        if (f.valueName.empty()) {
            app->add_flag(f.name, f.help)->group(f.group);
            continue;
        }
        app->add_option(f.name, values[f.name], f.help)
            ->type_name(f.valueName)
            ->allow_extra_args(false)
            ->group(f.group);
    }
    if (!spec.positional.empty()) app->add_option(spec.positional, positionals, spec.positionalHelp);
    return app;
}

}  // namespace

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
    return nearestWord(word, candidates);
}

namespace {

constexpr size_t kFlagColumn = 34;   // where a flag's help starts

std::string wrapLine(const std::string& line, size_t width) {
    if (line.size() <= width) return line;
    const size_t lead = line.find_first_not_of(' ');
    size_t hang = lead;
    const size_t gap = line.find("  ", lead);
    if (gap != std::string::npos) {
        const size_t column = line.find_first_not_of(' ', gap);
        if (column != std::string::npos && column <= width / 2) hang = column;
    }
    std::string out, rest = line;
    while (rest.size() > width) {
        size_t cut = rest.rfind(' ', width);
        if (cut == std::string::npos || cut <= hang) cut = rest.find(' ', width);   // a word wider than the line
        if (cut == std::string::npos) break;
        const size_t next = rest.find_first_not_of(' ', cut);
        if (next == std::string::npos) break;
        out += rest.substr(0, rest.find_last_not_of(' ', cut) + 1) + "\n";
        rest = std::string(hang, ' ') + rest.substr(next);
    }
    return out + rest;
}

std::string flagLine(const FlagSpec& f) {
    std::string left = "  " + f.name + (f.valueName.empty() ? "" : " " + f.valueName);
    if (left.size() + 2 > kFlagColumn) left += "\n" + std::string(kFlagColumn, ' ');
    else left.resize(kFlagColumn, ' ');
    return left + f.help;
}

}  // namespace

std::string wrapText(const std::string& text, size_t width) {
    std::string out;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        out += wrapLine(text.substr(start, end - start), width);
        if (end == text.size()) break;
        out += "\n";
        start = end + 1;
    }
    return out;
}

std::string helpText(const CommandSpec& spec) {
    std::string text = spec.description + "\n\nUsage: " + spec.program + " [OPTIONS]";
    if (!spec.positional.empty()) text += " " + spec.positional;
    text += "\n\nOptions:\n" + flagLine({"-h, --help", "", "print this help on stdout and exit 0"});
    // Every program takes it before its command's own flags (main: package/package.h).
    text += "\n" + flagLine({"--kernels", "DIR",
                             "load the kernel packages in DIR first (repeatable; also CAVITY_KERNELS, folders "
                             "separated by ':'; docs/packages.md)"});
    if (!spec.positional.empty()) text += "\n" + flagLine({spec.positional, "", spec.positionalHelp});
    std::vector<std::string> groups;
    for (const auto& f : spec.flags)
        if (std::find(groups.begin(), groups.end(), f.group) == groups.end()) groups.push_back(f.group);
    for (const auto& g : groups) {
        if (g != "Options") text += "\n\n" + g + ":";
        for (const auto& f : spec.flags)
            if (f.group == g) text += "\n" + flagLine(f);
    }
    text += "\n";
    if (!spec.footer.empty()) text += spec.footer + (spec.footer.back() == '\n' ? "" : "\n");
    text = wrapText(text);
    // Examples are never wrapped: each is one line to copy and paste.
    if (!spec.examples.empty()) {
        text += "\nExamples:\n";
        for (const auto& e : spec.examples) text += "  " + e + "\n";
    }
    return text;
}

Result<ParsedFlags> parseFlags(const CommandSpec& spec, const std::vector<std::string>& argv) {
    ParsedFlags out;
    std::vector<std::string> words;   // what CLI11 parses: every value as --flag=VALUE
    std::map<std::string, int> count;
    std::vector<std::string> known;
    for (const auto& f : spec.flags) {
        // A flag declared twice (a kernel parameter named like one of the
        // command's own flags) would abort inside CLI11.
        if (std::find(known.begin(), known.end(), f.name) != known.end())
            return internal(spec.program + ": " + f.name + " is declared twice (a kernel parameter named like a flag of "
                            "the command)");
        known.push_back(f.name);
    }
    for (size_t i = 0; i < argv.size(); ++i) {
        const std::string& w = argv[i];
        if (w == "--help" || w == "-h") {
            out.help = true;
            out.helpText = helpText(spec);
            return out;
        }
        const bool isFlag = w.size() > 2 && w.rfind("--", 0) == 0;
        if (!isFlag) {
            if (spec.positional.empty() || (w.size() > 1 && w[0] == '-'))
                return badInput("'" + w + "': unexpected argument (flags start with --; see " + spec.program + " --help)");
            out.positionals.push_back(w);
            continue;
        }
        const auto eq = w.find('=');
        const std::string name = w.substr(0, eq);
        const FlagSpec* f = findFlag(spec, name);
        if (!f) {
            const std::string near = nearest(name, known);
            return badInput(name + ": unknown flag (" + (near.empty() ? "" : "did you mean " + near + "? ") + "see " +
                            spec.program + " --help)");
        }
        if (++count[name] > 1 && !f->repeatable)
            return badInput(name + ": given twice (give one value, or one comma-separated list where the flag takes a list)");
        if (f->valueName.empty()) {
            if (eq != std::string::npos) return badInput(w + ": " + name + " takes no value");
            out.switches.insert(name);
            words.push_back(name);
            continue;
        }
        std::string value;
        if (eq != std::string::npos) {
            value = w.substr(eq + 1);
        } else {
            // The next word is the value, whatever it starts with, unless it
            // is one of this command's own flags: `--b-args '--frames 2'` is
            // `--b-args='--frames 2'`, and `--out --filter x` lacks its value.
            const auto isOwnFlag = [&](const std::string& next) {
                return next == "--help" || next == "-h" || findFlag(spec, next.substr(0, next.find('='))) != nullptr;
            };
            if (i + 1 >= argv.size() || isOwnFlag(argv[i + 1]))
                return badInput(name + ": missing value (" + name + " " + f->valueName + ")");
            value = argv[++i];
        }
        if (value.empty()) return badInput(name + " '': empty value (" + name + " " + f->valueName + ")");
        words.push_back(name + "=" + value);
    }
    std::map<std::string, std::vector<std::string>> values;
    std::vector<std::string> positionals;
    auto app = makeApp(spec, values, positionals);
    std::vector<std::string> reversed(words.rbegin(), words.rend());   // CLI11 takes argv reversed
    try {
        app->parse(reversed);
    } catch (const CLI::ParseError& e) {
        return badInput(spec.program + ": " + e.what());
    }
    // Back in command-line order, as the commands read them.
    std::map<std::string, size_t> next;
    for (const auto& w : words) {
        const auto eq = w.find('=');
        if (eq == std::string::npos) continue;
        const std::string name = w.substr(0, eq);
        out.values.emplace_back(name, values[name][next[name]++]);
    }
    return out;
}

}  // namespace cavity::flags
