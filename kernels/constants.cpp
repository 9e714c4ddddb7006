// Images the harness makes on the CPU for the kernels (ConstantImageDecl).
#include "families.h"
#include "kernel.h"

namespace cavity::kernels {

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
