// The CPU side of kernels/include/ssdo.glsl, ssdo_sampling.glsl,
// ssdo_fast.glsl and sky.glsl, shared by the SSDO references:
// ref_ssdo_sampling.cpp defines them; ref_ssdo.cpp (the direct passes, the
// blur and the composite) and ref_ssdo_indirect.cpp (the bounce passes) use
// them. Operation for operation where a value picks a texel, decides a test or
// reads the sky (ref_ssdo.cpp says how closely the GPU follows).
#pragma once

#include "reference/namespace.h"
#include "reference/pyramid.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <vector>

namespace cavity::reference::ssdo {

// --- the sky (include/sky.glsl) ---------------------------------------------

using Levels = std::vector<kernels::ConstantImageDecl::Level>;

// The constant image 'sky's levels from its own generator (a pass chain's
// read-back returns level 0 only); nullptr where there is no such image.
const Levels* skyLevels();

// The sky's (u, v) in the direction d.
Vec2 skyUv(Vec3 d);

// textureLod(sky, uv, lod) with a linear, mip-linear, clamp-to-edge sampler.
Vec3 sampleSky(const Levels& levels, Vec2 uv, float lod);

// The sky's irradiance about n from its 9 spherical-harmonic coefficients.
Vec3 skyAmbient(const std::vector<float>& sh, Vec3 n);

// --- the sampling (include/ssdo.glsl) ---------------------------------------

struct Basis {
    Vec3 t, b, n;
    float phiTurns;
};

// The receiver's frame about its normal n, and its rotation at (x, y).
Basis ssdoBasis(int x, int y, Vec3 n);

struct Sample {
    Vec3 dir;
    bool visible = true;
    int tx = -1, ty = -1;
};

// Direction i marched in `steps` points (1: seed 003's one random length).
Sample ssdoSample(const kernels::FrameUniforms& fr, const HostImage& position, const HostImage& normal, const Basis& f,
                  Vec3 p, int x, int y, int i, int count, int steps, float radius, float bias);

// SkyGather and its functions in include/ssdo_sampling.glsl.
struct SkyGather {
    float total = 0.0f, visible = 0.0f;
    Vec3 direct;

    void add(Vec3 n, Vec3 dir, Vec3 sky, bool open);
    float visibility(float contrast) const;
    Vec3 radiance(int count) const;
};

// bounceFrom() of include/ssdo_sampling.glsl.
Vec3 bounceFrom(Vec3 p, Vec3 n, Vec3 q, Vec3 m, Vec3 emitted, float radius, float distanceClamp);

// What both ssdo_fast passes walk (include/ssdo_fast.glsl's FastReceiver):
// inputs 0 and 1 are the pyramid's level 0 and the normal.
struct FastMarch {
    const kernels::FrameUniforms& f;
    std::vector<HostImage> zmip;
    const HostImage& normal;
    pyramid::View view;
    int n, steps;
    float radius, bias;

    explicit FastMarch(const Context& ctx);

    struct Receiver {
        float depth;
        Vec3 n, X;
        float level;   // N . X
        Basis basis;
    };

    // fastReceiver(): false on the background or a pixel without a normal.
    bool receiver(int x, int y, Receiver& r) const;

    // ssdoFastSample(): direction i marched, blocked by its first blocked
    // point, whose level-0 pixel (s.tx, s.ty) and depth are the sender.
    Sample sample(const Receiver& r, int x, int y, int i, float& senderDepth) const;
};

// The view ray through the centre of pixel (x, y), at depth 1.
Vec3 viewRay(const kernels::FrameUniforms& f, int x, int y);

// An RGBA texel of img.
void put(HostImage& img, int x, int y, Vec3 c, float a);

}  // namespace cavity::reference::ssdo
