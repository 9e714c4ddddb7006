// Synthetic performance histories for the change-point detector: per-commit
// medians at a level that steps where a regression was planted, times
// (1 + cv * normal noise). The noise comes from a fixed generator
// (splitmix64 and Box-Muller): the standard library's distributions may
// differ between library versions, and the tests must see the same series.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cavity::synthetic {

struct Gauss {
    uint64_t state;
    double uniform() {
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return (double((z ^ (z >> 31)) >> 11) + 0.5) / 9007199254740992.0;
    }
    double next() { return std::sqrt(-2 * std::log(uniform())) * std::cos(6.283185307179586 * uniform()); }
};

// `levels[i]` for `lengths[i]` points each, times (1 + cv * noise).
inline std::vector<double> series(const std::vector<double>& levels, const std::vector<size_t>& lengths, double cv, uint64_t seed) {
    Gauss g{seed};
    std::vector<double> out;
    for (size_t i = 0; i < levels.size(); ++i)
        for (size_t j = 0; j < lengths[i]; ++j) out.push_back(levels[i] * (1 + cv * g.next()));
    return out;
}

// n points at 1, and 1 + step from `at` (to `until`, exclusive, when given:
// a regression that was reverted).
inline std::vector<double> stepped(size_t n, size_t at, double step, double cv, uint64_t seed, size_t until = 0) {
    Gauss g{seed};
    std::vector<double> out;
    for (size_t i = 0; i < n; ++i) {
        const bool in = i >= at && (until == 0 || i < until);
        out.push_back((in ? 1 + step : 1.0) * (1 + cv * g.next()));
    }
    return out;
}

}  // namespace cavity::synthetic
