// Images the harness makes on the CPU for the kernels (ConstantImageDecl):
// the 4x4 rotation-noise tile the hemisphere kernels read, and the sky
// panorama with its mips that SSDO reads, whose generators are in
// noise_tables.cpp, sky_panorama.cpp and sky_sh.cpp.
#include "families.h"
#include "kernel.h"
#include "screen_space_tables.h"

namespace cavity::kernels {

std::vector<ConstantImageDecl> screenSpaceConstants() {
    ConstantImageDecl noise;
    noise.name = "noise4x4";
    noise.format = gpu::Format::RGBA32F;
    noise.make = [](const ParamValues&) { return std::vector<ConstantImageDecl::Level>{noiseTile()}; };
    // RGBA32F rather than 16F: sampled with linear filtering, and the CPU
    // reference reads the very floats made here, no half rounding between.
    ConstantImageDecl sky;
    sky.name = "sky";
    sky.format = gpu::Format::RGBA32F;
    sky.make = [](const ParamValues&) { return skyLevels(); };
    return {noise, sky};
}


const std::vector<ConstantImageDecl>& constantImages() {
    static const std::vector<ConstantImageDecl> images = screenSpaceConstants();
    return images;
}

const ConstantImageDecl* findConstant(const std::string& name) {
    for (const auto& c : constantImages())
        if (c.name == name) return &c;
    return nullptr;
}

}  // namespace cavity::kernels
