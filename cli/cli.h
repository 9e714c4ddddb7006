// The cavity command's subcommands. What they share with cavity_render and
// cavity_bench (flags, value parsers, shard sources, `quality`) is the flags
// library (flags/), whose names they use are imported below one by one.
#pragma once

#include "flags.h"
#include "imports.h"
#include "quality_command.h"
#include "shard_sources.h"
#include "values.h"

#include <string>
#include <vector>

namespace cavity::cli {


using flags::addKernelSource;
using flags::CommandSpec;
using flags::defaultBaselines;
using flags::EnvLookup;
using flags::exitCode;
using flags::fail;
using flags::FlagSpec;
using flags::helpText;
using flags::kernelHelp;
using flags::kernelParamFlags;
using flags::kHelpWidth;
using flags::nearest;
using flags::ParsedFlags;
using flags::parseFilter;
using flags::parseFlags;
using flags::parseInt;
using flags::parseNumber;
using flags::parseShard;
using flags::processEnv;
using flags::qualityCommand;
using flags::resolveShard;
using flags::Shard;
using flags::splitList;
using flags::storeCacheFlag;
using flags::storeFlag;
using flags::touchShardStatusFiles;
using flags::wrapText;

// Subcommands; each returns the process exit code.
int runCommand(const std::vector<std::string>& args);
int gateCommand(const std::vector<std::string>& args);
int baselinesCommand(const std::vector<std::string>& args);
int approveCommand(const std::vector<std::string>& args);   // cavity baselines approve
int migrateCommand(const std::vector<std::string>& args);   // cavity baselines migrate-digests
int compareCommand(const std::vector<std::string>& args);
int storeCommand(const std::vector<std::string>& args);     // cavity store check
int abCommand(const std::vector<std::string>& args);        // cavity ab
int historyCommand(const std::vector<std::string>& args);   // cavity history ingest|show|chart|alerts
int kernelsCommand(const std::vector<std::string>& args);   // cavity kernels list|show|check|coverage
int coverageCommand(const std::vector<std::string>& args);  // cavity kernels coverage
int kernelsCheck(const std::string& dir);                   // cavity kernels check DIR (kernels_check.cpp)

}  // namespace cavity::cli
