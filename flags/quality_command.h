// `quality`, the one command two front ends offer: cavity and cavity_render
// (which measures quality on a GPU machine without OpenImageIO). It lives in
// the flags library so that neither front end links the other.
#pragma once

#include <string>
#include <vector>

namespace cavity::flags {

// `program` starts every message: "cavity quality", "cavity_render quality".
int qualityCommand(const std::vector<std::string>& args, const std::string& program = "cavity quality");

}  // namespace cavity::flags
