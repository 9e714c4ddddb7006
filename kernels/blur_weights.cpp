#include "blur_weights.h"

#include <cmath>

namespace cavity::kernels {

std::vector<float> gaussianWeights(int radius) {
    // sigma = r / 2 puts the outermost tap at exp(-2) ~ 0.135 of the centre:
    // the kernel is cut where the Gaussian has mostly decayed. At r = 0
    // sigma would be 0; the kernel passes its input through instead.
    if (radius <= 0) return {1.0f};
    const double sigma = radius / 2.0;
    std::vector<double> w;
    double sum = 0;
    for (int i = 0; i <= radius; ++i) {
        const double x = i / sigma;
        w.push_back(std::exp(-0.5 * x * x));
        sum += w.back();
    }
    // Only w[0..r] is stored, but the kernel uses w[1..r] on both sides of
    // the centre: the full kernel sums to 2 sum - w[0]. Dividing by sum
    // alone would leave it summing to more than one, brightening the AO by
    // an amount that changes with the radius.
    const double total = 2.0 * sum - w[0];
    std::vector<float> out;
    for (double x : w) out.push_back(float(x / total));
    return out;
}

}  // namespace cavity::kernels
