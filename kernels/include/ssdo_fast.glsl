// SSDO's sampling (include/ssdo.glsl) on the linear-depth pyramid: the same
// basis, directions and marched points, each tested with one RG32F fetch of
// the pyramid (include/pyramid.glsl) and no position or normal, instead of
// against the G-buffer's position and normal. Shared by ssdo_fast_direct.glsl
// and ssdo_fast_indirect.glsl, which must walk the same points: the bounce
// re-uses the direct pass's blocked points as senders.
//
// A kernel including this file declares inputs named `zmip` (the pyramid)
// and `normal`.
#include "include/ssdo_sampling.glsl"
#include "include/pyramid.glsl"

// The direction count (up to 64) and the points a direction compiled in
// (KernelDecl::compileTime), as hemisphere_fast compiles its rays' shape:
// each point's distance along its direction is then a constant apart from
// the jitter, and the points are unrolled (Vulkan) or written out (GL,
// whose driver keeps a loop of constant count rolled). Past 64 directions
// both counts are the uniforms'.
#if defined(CAVITY_REPEAT_samples) && defined(CAVITY_REPEAT_steps)
#define SSDO_FAST_COMPILED 1
#define SSDO_FAST_COUNT CAVITY_CONST_samples
#define SSDO_FAST_STEPS CAVITY_CONST_steps
#else
#define SSDO_FAST_COUNT clamp(P.samples, 1, 256)
#define SSDO_FAST_STEPS clamp(P.steps, 1, 16)
#endif

struct FastSample {
    vec3 dir;
    bool visible;
    ivec2 sender;        // the level-0 pixel of the first blocked point's depth
    float senderDepth;   // its linear depth: the sender is positionAt(sender, senderDepth)
};

// Direction i of `count` from the receiver at view point p (at `level` =
// N . p along its normal), marched in SSDO_FAST_STEPS points out to R as
// ssdoSample marches it (point j at (j + 1 - u) R / steps, u drawn per
// pixel and direction), blocked by its first hidden point.
FastSample ssdoFastSample(PyramidView v, SsdoBasis f, vec3 p, float level, ivec2 pixel, int i, int count,
                          float radius, float bias) {
    FastSample s;
    s.dir = ssdoDirection(f, i, count);
    s.visible = true;
    float u = sampleHash(pixel, i);
    EXACT float perStep = portableReciprocal(float(SSDO_FAST_STEPS));
#define SSDO_FAST_POINT(j) { \
        EXACT float lambda = radius * ((float((j) + 1) - u) * perStep); \
        EXACT vec3 point = p + s.dir * lambda; \
        if (pyramidBlocks(v, f.n, level, point, pixel, bias, s.sender, s.senderDepth)) { \
            s.visible = false; \
            return s; \
        } \
    }
#if defined(SSDO_FAST_COMPILED) && !defined(VULKAN)
    CAVITY_REPEAT_steps(SSDO_FAST_POINT)
#elif defined(SSDO_FAST_COMPILED)
    CAVITY_UNROLL for (int j = 0; j < SSDO_FAST_STEPS; ++j) SSDO_FAST_POINT(j)
#else
    int steps = SSDO_FAST_STEPS;
    for (int j = 0; j < steps; ++j) SSDO_FAST_POINT(j)
#endif
    s.sender = ivec2(-1);
    s.senderDepth = 0.0;
    return s;
}

// A receiver of either pass: its depth, unit normal, view point, basis, and
// what its directions are marched with.
struct FastReceiver {
    float depth;
    vec3 n;
    vec3 X;
    float level;   // N . X
    SsdoBasis f;
    PyramidView view;
    int count;
};

// The receiver at `pixel`; false on the background (or a pixel without a
// normal), which both passes write as open.
bool fastReceiver(ivec2 pixel, out FastReceiver r) {
    r.depth = texelFetch(in_zmip, pixel, 0).r;
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    if (isBackground(r.depth) || lengthSquared(nrm) == 0.0) return false;
    r.n = portableNormalize(nrm);
    r.X = positionAt(pixel, r.depth);
    r.level = orderedDot(r.n, r.X);
    r.f = ssdoBasis(pixel, r.n);
    r.view = pyramidView();
    r.count = SSDO_FAST_COUNT;
    return true;
}

// Direction i of the receiver at `pixel`, marched.
FastSample fastSample(FastReceiver r, ivec2 pixel, int i) {
    return ssdoFastSample(r.view, r.f, r.X, r.level, pixel, i, r.count, P.radius, P.bias);
}
