// The tables the screen-space kernels read that the CPU makes: the sample
// kernels of the hemisphere SSAO (noise_tables.cpp), the 4x4 rotation-noise
// tile (noise_tables.cpp), and the sky panorama (sky_panorama.cpp) with its
// spherical-harmonic projection (sky_sh.cpp). The kernels' packages name
// them as derived arrays (docs/packages.md); constants.cpp declares the images.
#pragma once

#include "kernel.h"

#include <vector>

namespace cavity::kernels {

// Room in the hemisphere kernel array: the largest --samples.
int maxKernelPoints();

// n points of seed 004's hemisphere kernel, and of the cosine-weighted ray
// kernel of hemisphere_cosine, as maxKernelPoints() vec4s.
std::vector<float> hemisphereKernel(int n);
std::vector<float> cosineKernel(int n, int stepsPerRay);

// 16 random unit vectors in the view xy plane, RGBA32F.
ConstantImageDecl::Level noiseTile();

// The sky panorama and every mip level down to 1x1; the view direction at
// panorama coordinates (u, v).
const std::vector<ConstantImageDecl::Level>& skyLevels();
void skyDirection(double u, double v, double& dx, double& dy, double& dz);

// Irradiance / pi of the panorama as 9 SH coefficients (vec4s).
std::vector<float> skySh();

// Sample i's spiral direction at phase 0, (cos, sin) of (i + 0.5) 7/9 turns,
// one vec4 each for samples up to 256: the fast Alchemy kernel turns it by
// the pixel's phase once computed, where evaluating cos and sin per sample
// was a sixth of the pass on the H200 (docs/roofline.md). Whatever the
// table's last bits, the shader and the CPU reference read the same ones.
std::vector<float> spiralTable();

}  // namespace cavity::kernels
