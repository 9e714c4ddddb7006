// The images the harness makes on the CPU for the kernels, which the CPU
// references read as the GPU does (constants.cpp).
#pragma once

#include "kernel.h"

#include <vector>

namespace cavity::kernels {

std::vector<ConstantImageDecl> screenSpaceConstants();   // constants.cpp: noise tile, sky panorama

}  // namespace cavity::kernels
