// quality.html, written by `quality --out`: each kernel's AO beside the
// ground truth and its signed error map, all maps on one scale, and the
// ranking with each MAE's interval.
#pragma once

#include "measure/quality.h"
#include "result.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace cavity::flags {

// The error a map's colour saturates at: |AO - truth| of this is full colour
// on every map, so that maps compare at a glance.
constexpr double kErrorMapScale = 0.25;

// The page for quality.json's `doc` and the rows it was made from (with
// their images: QualityOptions::keepImages), self-contained: the images
// travel in it as base64 bytes and its script draws them.
std::string qualityPage(const nlohmann::json& doc, const std::vector<measure::QualityRow>& rows);

}  // namespace cavity::flags
