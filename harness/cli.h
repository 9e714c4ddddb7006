// Command-line plumbing shared by the cavity subcommands: a flag reader whose
// every error names the flag, the value and what is allowed.
#pragma once

#include "result.h"

#include <string>
#include <vector>

namespace cavity::cli {

class Args {
public:
    Args(std::vector<std::string> a) : a_(std::move(a)) {}
    bool done() const { return i_ >= a_.size(); }
    const std::string& peek() const { return a_[i_]; }
    std::string next() { return a_[i_++]; }
    // The value after a flag, or an error naming the flag.
    Result<std::string> value(const std::string& flag);

private:
    std::vector<std::string> a_;
    size_t i_ = 0;
};

Result<int> parseInt(const std::string& flag, const std::string& text, int lo, int hi);
// A finite number in [lo, hi]; "nan", "inf", "1e999" and trailing text fail.
Result<double> parseNumber(const std::string& flag, const std::string& text, double lo, double hi);
std::vector<std::string> splitList(const std::string& text);   // "8,16,32"
// "--shard I/N": (I, N) with 0 <= I < N.
Result<std::pair<int, int>> parseShard(const std::string& text);

// Exit code for an error, as documented in README.md ("Exit codes").
int exitCode(const Error& e);

// Subcommands; each returns the process exit code.
int runCommand(const std::vector<std::string>& args);
int gateCommand(const std::vector<std::string>& args);
int baselinesCommand(const std::vector<std::string>& args);
int compareCommand(const std::vector<std::string>& args);
// `program` starts every message: "cavity quality", "cavity_render quality".
int qualityCommand(const std::vector<std::string>& args, const std::string& program = "cavity quality");

}  // namespace cavity::cli
