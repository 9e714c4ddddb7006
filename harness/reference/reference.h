// CPU references: a plain C++ implementation of every kernel, written for
// clarity rather than speed, as an oracle the GPU results are tested against.
// They mirror the GLSL bodies' maths (float precision, the same hashes and
// texel addressing) but share no code with them.
#pragma once

#include "reference/namespace.h"
#include "core/image.h"
#include "kernel.h"

#include <map>
#include <string>
#include <vector>

namespace cavity::reference {

struct Context {
    const kernels::KernelDecl& kernel;
    const kernels::ParamValues& params;                      // complete (withDefaults)
    const std::map<std::string, std::vector<float>>& arrays;  // from kernel.derive
    const kernels::FrameUniforms& frame;
    std::vector<const HostImage*> inputs;                    // in kernel.inputs order
};

// Runs the reference of ctx.kernel; outputs are in kernel.outputs order, each
// frame.size[0] x frame.size[1] with channelCount(output format) channels.
// Fails (Internal) when the kernel has no reference.
Result<std::vector<HostImage>> run(const Context& ctx);
// Whether the kernel has a CPU reference: its package names one
// (`reference = "NAME"`, KernelDecl::reference) that is registered here. A
// kernel package may have none: its images are then gated by approved
// digests alone.
bool hasReference(const std::string& kernel);
// Whether a reference of this name is registered, and every such name.
bool isReference(const std::string& name);
std::vector<std::string> referenceNames();

// The linear-depth pyramid's `levels` levels rebuilt from level 0, as
// kernels/passes/depth_pyramid/depth_pyramid.glsl builds them (ref_fast.cpp).
std::vector<HostImage> pyramidLevels(const HostImage& level0, int levels);

}  // namespace cavity::reference

namespace cavity::reference {

// One reference function per kernel shader, registered under a name that a
// kernel package's `reference` line gives (the name of the kernel it was
// written for); each family's file (ref_*.cpp) returns its table, and
// reference.cpp's run() looks the kernel's reference up in all of them.
using RefFn = Result<std::vector<HostImage>> (*)(const Context&);
struct RefEntry {
    const char* kernel;   // the reference's name
    RefFn fn;
};
std::vector<RefEntry> screenSpaceRefs();   // ref_hemisphere.cpp, ref_ssdo.cpp, ref_halfres.cpp (via refs_screen_space.cpp)
std::vector<RefEntry> sdfAoRefs();         // ref_sdf_ao.cpp
std::vector<RefEntry> fastRefs();          // ref_fast.cpp

}  // namespace cavity::reference
