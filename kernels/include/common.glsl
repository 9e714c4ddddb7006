// Shared conventions and the few maths helpers whose bits matter.
//
// The CPU references (harness/reference/portable_math.h) compute the same
// quantities with the same operations in the same order. Wherever a value
// feeds a discrete decision (floor() to a sample pixel, a radius test), a
// one-ulp difference between the GPU and the CPU would move a sample to
// another pixel and change the AO by far more than the tests allow. So such
// values are built only from +, -, * (correctly rounded everywhere) and are
// declared `precise`, which forbids fusing a*b+c into one fma: EXACT below,
// which the preamble (kernels/assemble.cpp) defines as `precise`, or as
// nothing for a kernel run with --exact 0. Then CAVITY_INEXACT is defined
// too, and the helpers here use the hardware's own division, inverse square
// root and sine: faster, and the CPU reference holds to a stated tolerance
// instead of bit for bit (docs/kernels.md, "The precision contract").

const float PI = 3.14159265;
const float TWO_PI = 6.2831855;

// Linear depth 0 marks background (the ray missed) in every G-buffer image.
bool isBackground(float linearDepth) {
    return linearDepth <= 0.0;
}

// Whether `pixel` is in this pass's image, on either side: one unsigned
// test, a negative coordinate wraps past any size. A kernel that declares
// wholeWorkgroups (kernels/kernel.h) also runs past the edge, and writes
// nothing there.
bool inImage(ivec2 pixel) {
    return all(lessThan(uvec2(pixel), uvec2(frame.size)));
}

// View-space direction through the centre of `pixel`, at z = -1. Row 0 is
// the top of the image and +Y is up, hence the minus on y.
vec3 viewRayAt(ivec2 pixel) {
    vec2 ndc = (vec2(pixel) + 0.5) * frame.invSize * 2.0 - 1.0;
    return vec3(ndc.x * frame.camera.x, -ndc.y * frame.camera.y, -1.0);
}

// x*x + y*y + z*z in a fixed order: dot() leaves the order of the additions
// to the implementation.
float lengthSquared(vec3 v) {
    EXACT float r = v.x * v.x + v.y * v.y + v.z * v.z;
    return r;
}

// (cos, sin) of 2*pi*turns. GLSL's sin/cos need only be accurate to 2^-11
// (Vulkan) and differ between drivers and libm, so this is a fixed
// polynomial: reduce to the nearest quarter turn, then Taylor series to x^9
// on |x| <= pi/4 (error below 1e-7, well under what AO can show).
vec2 cosSinTurns(float turns) {
#ifdef CAVITY_INEXACT
    float a = turns * TWO_PI;
    return vec2(cos(a), sin(a));
#else
    EXACT float t = turns - floor(turns);
    EXACT float quarter = floor(t * 4.0 + 0.5);
    EXACT float r = t - quarter * 0.25;
    EXACT float x = r * TWO_PI;
    EXACT float x2 = x * x;
    EXACT float s = x * (1.0 + x2 * (-0.16666667 + x2 * (0.008333334 + x2 * (-0.0001984127 + x2 * 2.7557319e-06))));
    EXACT float c = 1.0 + x2 * (-0.5 + x2 * (0.041666668 + x2 * (-0.0013888889 + x2 * 2.4801588e-05)));
    int q = int(quarter) & 3;
    if (q == 0) return vec2(c, s);
    if (q == 1) return vec2(-s, c);
    if (q == 2) return vec2(-c, -s);
    return vec2(s, -c);
#endif
}

// 1 / x for x != 0 (either sign: the int subtraction wraps, and the estimate
// keeps the sign), the same bits on every implementation. A GLSL division
// may be off by 2.5 ulp (and often is a reciprocal times a multiply), so
// this starts from an exponent-bit estimate and refines it with Newton
// steps y' = y (2 - x y), each of which squares the estimate's relative
// error: 5e-2 -> 2.6e-3 -> 6.6e-6 -> 4e-11, so three leave only float
// rounding (under 3 ulp; exactness is not the point, agreement is).
float portableReciprocal(float x) {
#ifdef CAVITY_INEXACT
    return 1.0 / x;
#else
    EXACT float y = intBitsToFloat(0x7EF311C7 - floatBitsToInt(x));
    y = y * (2.0 - x * y);
    y = y * (2.0 - x * y);
    y = y * (2.0 - x * y);
    return y;
#endif
}
