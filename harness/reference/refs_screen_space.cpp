// The screen-space family's reference table, and the helpers its three
// files share: the CPU side of kernels/include/screen_space.glsl, the same
// operations in the same order (this library is built with
// -ffp-contract=off, as the GLSL marks these values `precise`).
//
// ref_hemisphere.cpp, ref_halfres.cpp and ref_ssdo.cpp declare what they use
// of this file in a `screen` block at their top.
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <array>
#include <bit>

namespace cavity::reference {

// ref_hemisphere.cpp
Result<std::vector<HostImage>> depthFromPosition(const Context& ctx);
Result<std::vector<HostImage>> hemisphere(const Context& ctx);
Result<std::vector<HostImage>> blurBox(const Context& ctx);
// ref_blur_box_depth.cpp
Result<std::vector<HostImage>> blurBoxDepth(const Context& ctx);
// ref_depth_half.cpp
Result<std::vector<HostImage>> depthFromPositionHalf(const Context& ctx);
// ref_halfres.cpp
Result<std::vector<HostImage>> downsampleDepth(const Context& ctx);
Result<std::vector<HostImage>> downsamplePyramid(const Context& ctx);
Result<std::vector<HostImage>> upsampleBilateral(const Context& ctx);
Result<std::vector<HostImage>> upsampleComposite(const Context& ctx);
// ref_ssdo.cpp
Result<std::vector<HostImage>> ssdoDirect(const Context& ctx);
Result<std::vector<HostImage>> blurBilateralSsdo(const Context& ctx);
Result<std::vector<HostImage>> ssdoIndirect(const Context& ctx);
Result<std::vector<HostImage>> compositeSsdo(const Context& ctx);
Result<std::vector<HostImage>> ssdoFastDirect(const Context& ctx);
Result<std::vector<HostImage>> ssdoFastIndirect(const Context& ctx);

std::vector<RefEntry> screenSpaceRefs() {
    return {
        {"depth_from_position", depthFromPosition},
        {"hemisphere", hemisphere},
        {"blur_box", blurBox},
        {"downsample_depth", downsampleDepth},
        // The same texels, and the depth as the pyramid's level 0 (its other
        // levels are checked against pyramidLevels by the tests).
        {"downsample_pyramid", downsamplePyramid},
        {"upsample_bilateral", upsampleBilateral},
        {"upsample_composite", upsampleComposite},
        {"ssdo", ssdoDirect},
        {"blur_bilateral_ssdo", blurBilateralSsdo},
        {"ssdo_indirect", ssdoIndirect},
        {"composite_ssdo", compositeSsdo},
        // The fixed variants that run the seeds' shaders with other defaults
        // (ssdo_marched, ssdo_marched_indirect, hemisphere_cosine) name the
        // seeds' references in their packages.
        {"blur_box_depth", blurBoxDepth},
        {"depth_from_position_half", depthFromPositionHalf},
        // the fast SSDO, on the depth pyramid (the separable pair is in ref_fast.cpp)
        {"ssdo_fast", ssdoFastDirect},
        {"ssdo_fast_indirect", ssdoFastIndirect},
    };
}

namespace screen {

float inverseSqrt(float x) {
    const float h = 0.5f * x;
    float y = std::bit_cast<float>(int32_t(0x5F375A86) - (std::bit_cast<int32_t>(x) >> 1));
    for (int i = 0; i < 4; ++i) y = y * (1.5f - h * y * y);
    return y;
}

Vec3 normalizeExact(Vec3 v) { return v * inverseSqrt(lengthSquared(v)); }

// tangentFrame() of include/screen_space.glsl: Gram-Schmidt of (r, 0)
// against the unit normal n, or of its perpendicular where the two are
// parallel.
void tangentFrame(Vec2 r, Vec3 n, Vec3& t, Vec3& b) {
    Vec3 rv{r.x, r.y, 0.0f};
    t = rv - n * dot(rv, n);
    if (lengthSquared(t) < 1e-6f) {
        rv = {-r.y, r.x, 0.0f};
        t = rv - n * dot(rv, n);
    }
    t = normalizeExact(t);
    b = cross(n, t);
}

std::array<float, 4> mulPoint(const float* m, Vec3 v, float w) {
    // Column c of the GLSL mat4 is m[4c .. 4c+3]; the sum runs over the
    // columns in order, as mulPoint in screen_space.glsl spells it out.
    std::array<float, 4> r{};
    for (int row = 0; row < 4; ++row) r[size_t(row)] = m[0 + row] * v.x + m[4 + row] * v.y + m[8 + row] * v.z + m[12 + row] * w;
    return r;
}

Vec3 viewFromDepth(const kernels::FrameUniforms& f, int tx, int ty, float depth) {
    const float ndcX = (float(tx) + 0.5f) * f.invSize[0] * 2.0f - 1.0f;
    const float ndcY = (float(ty) + 0.5f) * f.invSize[1] * 2.0f - 1.0f;
    const auto v = mulPoint(f.invProj, {ndcX, ndcY, depth}, 1.0f);
    const float r = portableReciprocal(v[3]);
    return {v[0] * r, v[1] * r, v[2] * r};
}

bool texelOfView(const kernels::FrameUniforms& f, Vec3 p, int& tx, int& ty) {
    const auto clip = mulPoint(f.proj, p, 1.0f);
    tx = ty = -1;
    if (clip[3] <= 0.0f) return false;
    const float r = portableReciprocal(clip[3]);
    const float u = clamp(clip[0] * r * 0.5f + 0.5f, -1.0f, 2.0f);
    const float v = clamp(clip[1] * r * 0.5f + 0.5f, -1.0f, 2.0f);
    tx = int(std::floor(u * float(f.size[0])));
    ty = int(std::floor(v * float(f.size[1])));
    return true;
}

bool texelInside(const kernels::FrameUniforms& f, int tx, int ty) {
    return tx >= 0 && ty >= 0 && tx < f.size[0] && ty < f.size[1];
}

float sampleHash(int x, int y, int i) {
    return hashToUnit(pcgHash(pcgHash(uint32_t(x) + uint32_t(y) * 65521u) + uint32_t(i)));
}

float smoothstep01(float x) {
    const float t = clamp(x, 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

Vec3 texel3(const HostImage& img, int x, int y) { return {img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)}; }

// include/screen_space.glsl's halfTexelRayHit in its exact operations.
bool halfTexelRayHit(const kernels::FrameUniforms& f, int x, int y, Vec3 p, Vec3 n, Vec3& hit) {
    const float ndcX = (float(x) + 0.5f) * f.invSize[0] * 2.0f - 1.0f;
    const float ndcY = (float(y) + 0.5f) * f.invSize[1] * 2.0f - 1.0f;
    const Vec3 ray{ndcX * f.camera[0], -ndcY * f.camera[1], -1.0f};
    const float facing = dot(n, ray);
    if (lengthSquared(n) > 0.0f && facing < 0.0f) {
        const float t = dot(n, p) * portableReciprocal(facing);
        const float moved = std::fabs(t + p.z);
        if (t > 0.0f && moved <= 0.05f * -p.z) {
            hit = ray * t;
            return true;
        }
    }
    return false;
}

Status requireInput(const Context& ctx, size_t i, int width, int height, int minChannels) {
    const HostImage& in = *ctx.inputs.at(i);
    const std::string what = "reference " + ctx.kernel.name + ": input '" + ctx.kernel.inputs[i].name + "' ";
    if ((width > 0 && in.width != width) || (height > 0 && in.height != height))
        return internal(what + "is " + std::to_string(in.width) + "x" + std::to_string(in.height) + ", expected " +
                        std::to_string(width) + "x" + std::to_string(height));
    if (in.channels < minChannels)
        return internal(what + "has " + std::to_string(in.channels) + " channels, needs " + std::to_string(minChannels));
    return {};
}

}  // namespace screen

}  // namespace cavity::reference
