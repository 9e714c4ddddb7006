#include "stats/stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cavity::stats {

double percentile(std::vector<double> s, double p) {
    if (s.empty()) return 0;
    std::sort(s.begin(), s.end());
    const double rank = p * double(s.size() - 1);
    const size_t lo = size_t(std::floor(rank)), hi = size_t(std::ceil(rank));
    return s[lo] + (s[hi] - s[lo]) * (rank - double(lo));
}

Stats summarize(std::vector<double> s) {
    Stats st;
    st.count = int(s.size());
    if (s.empty()) return st;
    std::sort(s.begin(), s.end());
    st.min = s.front();
    st.max = s.back();
    st.median = percentile(s, 0.5);
    st.p90 = percentile(s, 0.9);
    st.mean = std::accumulate(s.begin(), s.end(), 0.0) / double(s.size());
    double ss = 0;
    for (double x : s) ss += (x - st.mean) * (x - st.mean);
    st.stddev = s.size() > 1 ? std::sqrt(ss / double(s.size() - 1)) : 0.0;
    st.cv = st.mean > 0 ? st.stddev / st.mean : 0.0;
    return st;
}

}  // namespace cavity::stats