// The three formats' readers behind readRunFile (run_file.h); each fills
// `out`'s metadata and series from the parsed document.
#pragma once

#include "history/run_file.h"

#include <nlohmann/json.hpp>

namespace cavity::history {

Status readBenchmark(const nlohmann::json& doc, RunFile& out);
Status readResults(const nlohmann::json& doc, RunFile& out);
Status readGate(const nlohmann::json& doc, RunFile& out);

// "gl" or "vk": the API word of a configuration id
// ("corner/alchemy/n16/b4/full/160x90/gl/compute"), "" when it has none.
std::string apiOfId(const std::string& id);

}  // namespace cavity::history
