// The first slice's reference functions and what they share. Each ref_*.cpp
// mirrors one kernels/*.glsl body; reference.cpp dispatches to them.
#pragma once

#include "reference/namespace.h"
#include "reference/reference.h"

#include <initializer_list>
#include <string>
#include <vector>

namespace cavity::reference {

Result<std::vector<HostImage>> gbufferSdf(const Context& ctx);      // ref_gbuffer_sdf.cpp
Result<std::vector<HostImage>> alchemy(const Context& ctx);         // ref_alchemy.cpp
Result<std::vector<HostImage>> blurBilateral(const Context& ctx);   // ref_blur_bilateral.cpp
Result<std::vector<HostImage>> composite(const Context& ctx);       // ref_composite.cpp
// The composite's colour of every pixel of ctx.frame into `color` (4 channels).
void compositeInto(const Context& ctx, const HostImage& ao, const HostImage& normal, const HostImage& albedo,
                   HostImage& color);

// The kernel's outputs, frame-sized and zeroed, in declaration order.
std::vector<HostImage> makeOutputs(const Context& ctx);
// A parameter as the uniform block carries it: Int/Bool/Enum rounded to int.
int intParam(const Context& ctx, const std::string& name);
float floatParam(const Context& ctx, const std::string& name);
// Fails unless every input has the output's size (the kernel texelFetches
// its inputs at the output pixel) and input i at least minChannels[i]
// channels.
Status requireInputs(const Context& ctx, std::initializer_list<int> minChannels);
// A derived array (kernel.derive), or an empty one.
const std::vector<float>& array(const Context& ctx, const std::string& name);


inline bool isBackground(float linearDepth) { return linearDepth <= 0.0f; }

}  // namespace cavity::reference
