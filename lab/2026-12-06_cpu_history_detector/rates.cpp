// The detector's rates on synthetic 30-commit histories (tests/history_synthetic.h).
// Built by lab/2026-12-06_cpu_history_detector/rates.sh against the harness library.
#include "history/edivisive.h"
#include "history_synthetic.h"

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

using namespace cavity;
using history::ChangePoint;

namespace {
int trials = 200;
struct Rate { int hit = 0, other = 0, n = 0; };
void report(const std::string& what, const Rate& r) {
    std::printf("%-48s %4d / %-4d at the commit, %4d other alerts\n", what.c_str(), r.hit, r.n, r.other);
}
Rate run(const std::function<std::vector<double>(uint64_t, size_t&)>& make, const std::function<bool(const ChangePoint&, size_t)>& hit) {
    Rate r;
    for (int t = 0; t < trials; ++t) {
        size_t at = 0;
        const auto x = make(uint64_t(t) * 7919 + 13, at);
        const auto cps = history::detectChangePoints(x);
        bool found = false;
        for (const auto& c : cps) {
            if (hit(c, at) && !found) found = true;
            else if (c.change() < 0 && c.index > at) continue;   // the revert
            else r.other++;
        }
        r.hit += found;
        r.n++;
    }
    return r;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc > 1) trials = std::atoi(argv[1]);
    const size_t n = 30;
    for (double cv : {0.003, 0.01}) {
        const std::string noise = " noise " + std::to_string(cv * 100).substr(0, 3) + "%";
        for (double step : {0.015, 0.02, 0.03, 0.05, 0.10}) {
            auto r = run([&](uint64_t s, size_t& at) { at = 5 + s % 21; return synthetic::stepped(n, at, step, cv, s); },
                         [](const ChangePoint& c, size_t at) { return c.index == at && c.change() > 0; });
            report("step " + std::to_string(int(step * 1000) / 10.0).substr(0, 4) + "%" + noise, r);
        }
        for (size_t len : {3, 5, 8}) {
            auto r = run([&](uint64_t s, size_t& at) { at = 5 + s % 18; return synthetic::stepped(n, at, 0.05, cv, s, at + len); },
                         [](const ChangePoint& c, size_t at) { return c.index == at && c.change() > 0; });
            report("reverted +5% for " + std::to_string(len) + noise, r);
        }
        {
            // two +1.5% steps 10 apart: both named (hit counts the first; other counts the second when right)
            int both = 0, tot = 0, wrong = 0;
            for (int t = 0; t < trials; ++t) {
                const uint64_t s = uint64_t(t) * 7919 + 13;
                const size_t a = 6 + s % 8;
                auto x = synthetic::stepped(n, a, 0.015, cv, s);
                for (size_t i = a + 10; i < n; ++i) x[i] *= 1.015;
                bool fa = false, fb = false;
                for (const auto& c : history::detectChangePoints(x)) {
                    if (c.index == a) fa = true;
                    else if (c.index == a + 10) fb = true;
                    else wrong++;
                }
                both += fa && fb;
                tot++;
            }
            std::printf("%-48s %4d / %-4d both named, %4d other alerts\n", ("two +1.5% steps 10 apart" + noise).c_str(), both, tot, wrong);
        }
        {
            int alerts = 0, series = 0;
            for (int t = 0; t < trials * 5; ++t) {
                alerts += history::detectChangePoints(synthetic::stepped(n, 0, 0, cv, uint64_t(t) * 104729 + 1)).size() > 0;
                series++;
            }
            std::printf("%-48s %4d / %-4d series with an alert\n", ("flat" + noise).c_str(), alerts, series);
        }
        {
            // the newest commits: a 5% step 1, 2, 3 commits before the end
            for (size_t k : {1, 2, 3, 5}) {
                auto r = run([&](uint64_t s, size_t& at) { at = n - k; return synthetic::stepped(n, at, 0.05, cv, s); },
                             [](const ChangePoint& c, size_t at) { return c.index == at && c.change() > 0; });
                report("+5% with " + std::to_string(k) + " commits after" + noise, r);
            }
        }
    }
}
