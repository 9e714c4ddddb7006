// Kernel parameters: every name declared once, with its type, range, unit and
// help (params.cpp). A kernel refers to a declaration (KernelParam) and may
// give it its own default where its seed was tuned for another value (the SDF
// AO family's radius and strength), and a note on what it does with it; the
// name, range, unit and help stay one. The CLI flags, the config parser, the
// uniform block and the error messages read these declarations.
//
// Values travel as doubles (ParamValues): an Int, Bool or Enum value is an
// exact integer from the moment it is parsed (parseValue refuses 16.5), so
// intValue() below is the one place a value becomes an int.
#pragma once

#include "result.h"

#include <deque>
#include <map>
#include <string>
#include <vector>

namespace cavity::kernels {

enum class ParamType { Int, Float, Bool, Enum };

// Int, Bool and Enum are ints in the uniform block; Float is a float.
inline bool isIntegral(ParamType t) { return t != ParamType::Float; }

struct ParamDecl {
    std::string name;          // the flag (--name), the GLSL field (P.name), the results key
    ParamType type = ParamType::Float;
    double def = 0;            // the default of every kernel that does not give its own
    double min = 0, max = 0;   // inclusive; for Enum: index range of choices
    std::string unit;          // "world units", "px", "samples", ""
    std::string help;
    std::vector<std::string> choices;   // Enum only: names, value = index
    bool minExclusive = false;          // e.g. R > 0
};

// Every kernel parameter the harness knows, one declaration per name, in the
// order --help lists them: the built-in ones, then those kernel packages
// declared (a deque, so that a declaration's address never moves).
const std::deque<ParamDecl>& paramDecls();
// Adds a package's parameter; its name must be new (the caller checks).
const ParamDecl* declareParam(ParamDecl p);
// Drops the package parameters declared after the first `count`: a folder of
// packages that failed to load leaves none behind.
void forgetParamsAfter(size_t count);
// The declaration of a name, or null.
const ParamDecl* findParam(const std::string& name);
// Whether the harness itself reads the parameter, so that a kernel that
// declares it need not read it from P: assemble() (exact, interleave) or
// the pipeline, which picks passes by it (pyramid_per_level, fused_tail,
// depth_aware_box). `cavity kernels check` holds every other declared
// parameter to the shader.
bool readByHarness(const std::string& name);

// A kernel's use of a declared parameter.
struct KernelParam {
    const ParamDecl* decl = nullptr;
    double def = 0;            // this kernel's default (decl->def unless its seed needs another)
    std::string note;          // what this kernel does with it, for --help; may be empty

    const std::string& name() const { return decl->name; }
    ParamType type() const { return decl->type; }
};

// The kernel's use of the declaration `name` at the declared default, or at
// its own. A name that is not declared is a mistake in the registry, caught
// when the registry is built (std::logic_error) and by tests/test_params.cpp.
KernelParam use(const std::string& name, std::string note = "");
KernelParam use(const std::string& name, double def, std::string note);

using ParamValues = std::map<std::string, double>;

// The value a checked parameter value stands for: a float's as the shader
// gets it, a 32-bit float, written back as the shortest decimal that reads
// as that float (0.50000001 is 0.5, 0.6 stays 0.6); -0 as 0. Values the
// shader cannot tell apart are then one configuration, with one id.
double canonicalValue(const ParamDecl& p, double v);

// The one parse of a parameter's text: a number (an integer for Int and Bool),
// or an Enum choice's name; checked against the range. The message names the
// flag, the value and what is allowed: "--samples 300: must be an integer in 1..256 (samples)".
Result<double> parseValue(const ParamDecl& p, const std::string& text);
// The same check for a value already held (matrices, tests, sweeps built in code).
Status checkValue(const ParamDecl& p, double value);
// What a parameter accepts, as the messages say it: "a number > 0 and <= 100 (world units)".
std::string allowedValues(const ParamDecl& p);
// A value as --help and the messages write it: "0.5", or an Enum's choice name.
std::string valueText(const ParamDecl& p, double value);

// Typed reads of checked values: the one conversion of an Int, Bool or Enum
// parameter to int. `values` must hold `name` (withDefaults fills them).
int intValue(const ParamValues& values, const std::string& name);
int asInt(double checkedValue);
float floatValue(const ParamValues& values, const std::string& name);

}  // namespace cavity::kernels
