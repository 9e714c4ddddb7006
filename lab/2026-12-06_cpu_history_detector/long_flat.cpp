#include "history/edivisive.h"
#include "history_synthetic.h"
#include <cstdio>
#include <chrono>
using namespace cavity;
int main() {
    for (size_t n : {10, 30, 100, 300}) {
        int alerts = 0, series = 0;
        for (int t = 0; t < (n > 100 ? 200 : 1000); ++t) { alerts += history::detectChangePoints(synthetic::stepped(n, 0, 0, 0.01, t * 31 + 7)).size() > 0; series++; }
        std::printf("flat n=%zu: %d / %d\n", n, alerts, series);
    }
    auto t0 = std::chrono::steady_clock::now();
    size_t k = 0;
    for (int t = 0; t < 16 * 5; ++t) k += history::detectChangePoints(synthetic::stepped(3000, 1500, 0.05, 0.01, t)).size();
    std::printf("80 series of 3000: %.2f s, %zu points\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), k);
}
