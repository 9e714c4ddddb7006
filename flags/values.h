// Command-line plumbing shared by the cavity subcommands, cavity_render and
// cavity_bench (the flags library: the front ends' one shared part): value parsers whose every error names the flag, the value and
// what is allowed (the flags themselves are declared and parsed in flags.h).
#pragma once

#include "printable.h"
#include "imports.h"
#include "pipeline/pipeline.h"
#include "flags.h"
#include "result.h"

#include <functional>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace cavity::flags {


Result<int> parseInt(const std::string& flag, const std::string& text, int lo, int hi);
// A finite number in [lo, hi]; "nan", "inf", "1e999" and trailing text fail.
Result<double> parseNumber(const std::string& flag, const std::string& text, double lo, double hi);
// The same where [lo, hi] cannot say what is allowed (an open bound, no upper
// bound): `allowed` decides, `what` names it ("a number in (0, 1)").
Result<double> parseNumber(const std::string& flag, const std::string& text, const std::function<bool(double)>& allowed,
                           const std::string& what);
// "8,16,32" -> {"8", "16", "32"}; an empty list, an empty item ("8,,16")
// and an item given twice ("8,8": the same configuration twice) are errors.
Result<std::vector<std::string>> splitList(const std::string& flag, const std::string& text);
// --filter REGEX: an ECMAScript regex, searched in configuration ids; one
// that does not compile is an error naming the flag and why.
Result<std::regex> parseFilter(const std::string& flag, const std::string& text);
// --kernel-source NAME=FILE (cavity gate, cavity_render): kernels/NAME
// replaced by FILE's text. NAME must be a kernel source and given once; FILE
// a readable text file (no NUL byte) of at most 1 MiB. Adds it to both maps.
Status addKernelSource(const std::string& value, SourceOverrides& overrides, std::vector<ReplacedSource>& replaced);
// --store DIR|URL and --store-cache DIR (harness/store/store.h), as every
// command that reads or writes the image store declares them.
FlagSpec storeFlag();
FlagSpec storeCacheFlag();
// "--shard I/N": (I, N) with 0 <= I < N.
Result<std::pair<int, int>> parseShard(const std::string& text);

// One flag per kernel parameter name (--samples, --radius, ...), its help
// read from the declarations (kernels/kernel.h ParamDecl): what it does,
// default, range and unit, and which kernels take it. `skip`: names the
// command declares itself (--scene).
std::vector<FlagSpec> kernelParamFlags(const std::set<std::string>& skip = {});
// The kernels --kernel accepts, one a line with its summary (KernelDecl::summary).
// `heading` starts the list ("Kernels (--kernel)").
std::string kernelHelp(const std::string& heading = "Kernels (--kernel)");

// The baselines folder when --baselines is not given: baselines/ of the first
// folder from the working directory up that holds baselines/matrices.json,
// else the source tree's this binary was built from (CAVITY_SOURCE_DIR);
// neither: an error that says where it looked and to give --baselines.
Result<std::string> defaultBaselines();

// Exit code for an error, as documented in README.md ("Exit codes").
int exitCode(const Error& e);
// The edge of a command: prints "program: message" on stderr and returns
// the error's exit code.
using cavity::printable;   // base/printable.h: a message on one line
int fail(const std::string& program, const Error& e);

}  // namespace cavity::flags
