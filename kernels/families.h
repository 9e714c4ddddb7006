// Kernel families beyond the first slice, each declared in its own file and
// joined by registry.cpp's all().
#pragma once

#include "kernel.h"

#include <vector>

namespace cavity::kernels {

std::vector<KernelDecl> screenSpaceKernels();   // decl_screen_space.cpp: hemisphere, box blur, SSDO, half resolution
std::vector<KernelDecl> qualityVariantKernels();   // decl_quality_variants.cpp: ssdo_marched, blur_box_depth (issue 11)
std::vector<KernelDecl> sdfAoKernels();         // decl_sdf_ao.cpp: the SDF AO variants and the ground truth
std::vector<ConstantImageDecl> screenSpaceConstants();   // decl_screen_space.cpp: noise tile, sky panorama
// Texels of the sky panorama one SSDO direction's textureLod reads at `sky_lod`:
// 4 (bilinear) or 8 (trilinear between two levels). decl_screen_space.cpp.
double skyTexels(const ParamValues& v);

}  // namespace cavity::kernels
