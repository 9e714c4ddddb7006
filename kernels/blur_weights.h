// The 1-D Gaussian of the bilateral blur, computed on the CPU once per
// radius and handed to the kernel as a uniform array, so that changing the
// radius needs no recompile (McGuire et al., HPG 2011).
#pragma once

#include <vector>

namespace cavity::kernels {

// w[0..radius], normalised so that the symmetric kernel w[|i|], i in
// [-radius, radius], sums to one. Radius 0 gives {1}.
std::vector<float> gaussianWeights(int radius);

}  // namespace cavity::kernels
