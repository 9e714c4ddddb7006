#include "history/edivisive.h"
#include "history_synthetic.h"
#include <cstdio>
using namespace cavity;
int main() {
    int offby[5] = {0}, none = 0, n = 0;
    for (int t = 0; t < 400; ++t) {
        uint64_t s = uint64_t(t) * 7919 + 13;
        size_t at = 5 + s % 21;
        auto x = synthetic::stepped(30, at, 0.03, 0.01, s);
        auto cps = history::detectChangePoints(x);
        n++;
        if (cps.empty()) { none++; continue; }
        long best = 99;
        for (auto& c : cps) if (std::labs(long(c.index) - long(at)) < std::labs(best)) best = long(c.index) - long(at);
        if (std::labs(best) < 3) offby[std::labs(best)]++; else offby[3]++;
        if (best != 0 && t < 60) { std::printf("at %zu:", at); for (auto& c : cps) std::printf(" %zu(%.3g,p%.2g)", c.index, c.change(), c.pValue); std::printf("\n"); }
    }
    std::printf("exact %d off1 %d off2 %d far %d none %d of %d\n", offby[0], offby[1], offby[2], offby[3], none, n);
}
