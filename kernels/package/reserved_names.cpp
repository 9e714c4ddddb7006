// Names a package may not give a new parameter or array: each parameter
// becomes a flag of the commands that run kernels and a uniform of the
// shader, and each array a uniform block member (asFlag false: GLSL's
// words alone).
#include "package/toml_read.h"

#include <regex>
#include <set>
#include <string>

namespace cavity::kernels::toml_read {

bool reservedName(const std::string& name, bool asFlag) {
    // The commands' own flags (cavity run, gate, quality, cavity_bench,
    // cavity_render); tests/test_packages.py checks the list against their
    // --help.
    static const std::set<std::string> flags = {
        "backend", "baselines", "cost", "device", "expectations", "filter", "frames", "gbuffer", "help",
        "iterations", "kernel", "kernels", "list", "matrix", "name", "out", "plant", "quiet", "reach", "repeat", "res",
        "resolution", "retries", "scene", "shard", "stage", "store", "strict", "sweep", "table", "timing",
        "validation", "version", "view", "views", "warmup"};
    // GLSL 4.60's keywords and the words it reserves for the future, as far
    // as a-z names reach them; the type names the shaders use.
    static const std::set<std::string> glsl = {
        "active", "asm", "atomic_uint", "attribute", "bool", "break", "buffer", "bvec2", "bvec3", "bvec4", "case",
        "cast", "centroid", "class", "coherent", "common", "const", "continue", "default", "discard", "dmat2", "dmat3",
        "dmat4", "do", "double", "dvec2", "dvec3", "dvec4", "else", "enum", "extern", "external", "false", "filter",
        "fixed", "flat", "float", "for", "fvec2", "fvec3", "fvec4", "goto", "half", "highp", "hvec2", "hvec3",
        "hvec4", "if", "iimage2d", "image2d", "in", "inline", "inout", "input", "int", "interface", "invariant",
        "isampler2d", "ivec2", "ivec3", "ivec4", "layout", "long", "lowp", "mat2", "mat3", "mat4", "mediump",
        "namespace", "noinline", "noperspective", "out", "output", "partition", "patch", "precise", "precision",
        "public", "readonly", "resource", "restrict", "return", "sample", "sampler", "sampler2d", "short", "sizeof",
        "smooth", "static", "struct", "subroutine", "superp", "switch", "template", "texture", "this", "true",
        "typedef", "uimage2d", "uint", "union", "uniform", "unsigned", "using", "usampler2d", "uvec2", "uvec3",
        "uvec4", "varying", "vec2", "vec3", "vec4", "void", "volatile", "while", "writeonly", "shared",
        "subpassinput", "subpassinputms", "isubpassinput", "isubpassinputms", "usubpassinput", "usubpassinputms"};
    // The matrix types of every shape (mat2x3, dmat4x4) and the sampler,
    // texture and image types of every dimension (usampler2darray,
    // image1d, texturecube).
    static const std::regex families(
        "d?mat[234]x[234]|[iu]?(sampler|texture|image)(1d|2d|3d|cube|2drect|buffer|1darray|2darray|cubearray|2dms|"
        "2dmsarray)|sampler(1d|2d|2drect|cube|1darray|2darray|cubearray)shadow|samplershadow");
    // GLSL keeps gl_ names and any name with two underscores in a row.
    if (asFlag && (flags.count(name) || name.rfind("benchmark_", 0) == 0)) return true;
    // The words of the cost and paths formulas beside the parameters (a
    // pass's stage and workgroup, the image's size): a parameter of one of
    // these names was shadowed in one formula and read in the other.
    static const std::set<std::string> formulas = {"compute", "width", "height", "workgroup_x", "workgroup_y"};
    if (asFlag && formulas.count(name)) return true;
    return glsl.count(name) || std::regex_match(name, families) || name.rfind("gl_", 0) == 0 ||
           name.find("__") != std::string::npos;
}

}  // namespace cavity::kernels::toml_read
