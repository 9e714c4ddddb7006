// CAVITY_WORKGROUP=WxH: the compute workgroup shape every kernel runs in (W
// and H powers of two, W x H from 32 to 1024); none when unset or empty.
// Anything else fails with ErrorCode::BadInput naming the variable. Header
// only: the kernels apply it, and withEnvironment (backend.h) checks it when
// a command starts, before anything is written.
#pragma once

#include "result.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

namespace cavity::gpu {

inline Result<std::optional<std::pair<uint32_t, uint32_t>>> workgroupOverride() {
    const char* v = std::getenv("CAVITY_WORKGROUP");
    if (!v || !*v) return std::optional<std::pair<uint32_t, uint32_t>>{};   // unset or empty: each kernel's own
    const std::string text = v;
    auto pow2 = [](unsigned long n) { return n > 0 && (n & (n - 1)) == 0; };
    unsigned long x = 0, y = 0;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%lux%lu%c", &x, &y, &extra) != 2 || !pow2(x) || !pow2(y) || x * y < 32 || x * y > 1024)
        return badInput("CAVITY_WORKGROUP=" + text +
                        ": must be WxH, W and H powers of two, W x H from 32 to 1024 (unset: each kernel's own, mostly 16x16)");
    return std::optional<std::pair<uint32_t, uint32_t>>{{uint32_t(x), uint32_t(y)}};
}

}  // namespace cavity::gpu
