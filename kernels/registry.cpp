// The kernel registry: every kernel the harness can run. Each is a package
// (kernels/ao/<name>/, kernels/passes/<name>/: docs/packages.md), embedded in
// the binary and read when the registry is first asked for, in the order of
// its folder's path; a user's packages (--kernels) join it after them. The
// CLI flags, the config parser, the uniform block and the error messages are
// all generated from these declarations (kernel.h).
#include "kernel.h"
#include "package/package.h"

namespace cavity::kernels {

std::vector<KernelDecl>& registryForTests() {
    static std::vector<KernelDecl> kernels = [] {
        registryBuilding() = true;
        std::vector<KernelDecl> k;
        appendBuiltInPackages(k);
        registryBuilding() = false;
        return k;
    }();
    return kernels;
}

const std::vector<KernelDecl>& all() { return registryForTests(); }

bool declares(const KernelDecl& k, const std::string& name) {
    for (const auto& p : k.params)
        if (p.name() == name) return true;
    return false;
}

bool evaluatesScene(const KernelDecl& k) { return k.role != Role::GBuffer && declares(k, "scene"); }

}  // namespace cavity::kernels
