// Command-line plumbing shared by the cavity subcommands: a flag reader whose
// every error names the flag, the value and what is allowed.
#pragma once

#include "flags.h"
#include "result.h"

#include <set>
#include <string>
#include <vector>

namespace cavity::cli {

class Args {
public:
    // Flags in `repeatable` may be given more than once (--kernel-source A=x
    // --kernel-source B=y); any other flag given twice is an error, never
    // "the last one wins".
    Args(std::vector<std::string> a, std::set<std::string> repeatable = {})
        : a_(std::move(a)), repeatable_(std::move(repeatable)) {}
    bool done() const { return i_ >= a_.size(); }
    const std::string& peek() const { return a_[i_]; }
    std::string next() { return a_[i_++]; }
    // The value after a flag, or an error naming the flag: missing, empty, or
    // the flag given twice.
    Result<std::string> value(const std::string& flag);

private:
    std::vector<std::string> a_;
    std::set<std::string> repeatable_, seen_;
    size_t i_ = 0;
};

Result<int> parseInt(const std::string& flag, const std::string& text, int lo, int hi);
// A finite number in [lo, hi]; "nan", "inf", "1e999" and trailing text fail.
Result<double> parseNumber(const std::string& flag, const std::string& text, double lo, double hi);
// "8,16,32" -> {"8", "16", "32"}; an empty list, an empty item ("8,,16")
// and an item given twice ("8,8": the same configuration twice) are errors.
Result<std::vector<std::string>> splitList(const std::string& flag, const std::string& text);
// "--shard I/N": (I, N) with 0 <= I < N.
Result<std::pair<int, int>> parseShard(const std::string& text);

// One flag per kernel parameter name (--samples, --radius, ...), its help
// read from the declarations (kernels/kernel.h ParamDecl): what it does,
// default, range and unit, and which kernels take it. `skip`: names the
// command declares itself (--scene).
std::vector<FlagSpec> kernelParamFlags(const std::set<std::string>& skip = {});
// The kernels --kernel accepts, one a line with its summary (KernelDecl::summary).
std::string kernelHelp();

// The baselines folder when --baselines is not given: baselines/ of the first
// folder from the working directory up that holds baselines/matrices.json,
// else the source tree's this binary was built from (CAVITY_SOURCE_DIR);
// neither: an error that says where it looked and to give --baselines.
Result<std::string> defaultBaselines();

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
