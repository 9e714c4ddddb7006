// Kernel families beyond the first slice, each declared in its own file and
// joined by registry.cpp's all().
#pragma once

#include "kernel.h"

#include <vector>

namespace cavity::kernels {

std::vector<KernelDecl> screenSpaceKernels();   // decl_screen_space.cpp: hemisphere, box blur, SSDO, half resolution
std::vector<KernelDecl> qualityVariantKernels();   // decl_quality_variants.cpp: ssdo_marched, blur_box_depth
std::vector<KernelDecl> sdfAoKernels();         // decl_sdf_ao.cpp: the SDF AO variants and the ground truth
std::vector<ConstantImageDecl> screenSpaceConstants();   // decl_screen_space.cpp: noise tile, sky panorama
// Texels of the sky panorama one SSDO direction's textureLod reads at `sky_lod`:
// 4 (bilinear) or 8 (trilinear between two levels). decl_screen_space.cpp.
double skyTexels(const ParamValues& v);

// Texel sizes in bytes for the declarations' costs, from the backend's one
// table (gpu::bytesPerPixel).
constexpr double kRgba32f = gpu::bytesPerPixel(gpu::Format::RGBA32F);
constexpr double kRgba16f = gpu::bytesPerPixel(gpu::Format::RGBA16F);
constexpr double kRgba8 = gpu::bytesPerPixel(gpu::Format::RGBA8);
constexpr double kR32f = gpu::bytesPerPixel(gpu::Format::R32F);
// A texel of the depth pyramid: its depth and its source pixel.
constexpr double kRg32f = gpu::bytesPerPixel(gpu::Format::RG32F);
constexpr double kR16f = gpu::bytesPerPixel(gpu::Format::R16F);

// Levels of the linear-depth pyramid: 1920x1080 down to 120x67. Alchemy's
// largest sample offsets at R = 0.5 on our cameras are about 250 px, which
// ssao_alchemy_fast.glsl's level rule puts on level 4.
constexpr int kPyramidLevels = 5;

}  // namespace cavity::kernels
