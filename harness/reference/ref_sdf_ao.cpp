// References of the SDF AO family (kernels/sdf_ao_*.glsl, ground_truth.glsl):
// the same probes against the same scene (sdf_scenes.cpp), in float. The
// distance probes are continuous in their inputs, so GPU and CPU differ by
// float rounding (the GPU's sqrt, pow and exp2 are not exactly rounded);
// the ground truth's escape test is a yes/no per ray, so a ray that grazes
// an edge may go either way, a few rays in 1024 at most.
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/refs.h"
#include "reference/sdf_scenes.h"

#include <algorithm>
#include <cmath>

namespace cavity::reference {

namespace {

struct Surface {
    Vec3 position, normal;
    bool background;
};

struct SdfContext {
    Scene scene;
    Vec3 eye, right, up, forward;
    const HostImage* position;
    const HostImage* normal;

    Surface at(int x, int y) const {
        const float px = position->at(x, y, 0), py = position->at(x, y, 1), pz = position->at(x, y, 2);
        const Vec3 nv{normal->at(x, y, 0), normal->at(x, y, 1), normal->at(x, y, 2)};
        Surface s;
        s.background = isBackground(position->at(x, y, 3)) || dot(nv, nv) == 0.0f;
        s.position = eye + right * px + up * py - forward * pz;
        s.normal = s.background ? Vec3{0, 1, 0} : normalize(right * nv.x + up * nv.y - forward * nv.z);
        return s;
    }
    float map(Vec3 p) const { return sceneDistance(scene, p).distance; }
};

Result<SdfContext> sdfContext(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {4, 3}));
    SdfContext c;
    c.scene = Scene(std::clamp(intParam(ctx, "scene"), 0, kSceneCount - 1));
    const CameraPose pose = sceneCamera(c.scene, intParam(ctx, "view"));
    c.eye = pose.eye;
    c.forward = normalize(pose.target - pose.eye);
    c.right = normalize(cross(c.forward, Vec3{0, 1, 0}));
    c.up = cross(c.right, c.forward);
    c.position = ctx.inputs[0];
    c.normal = ctx.inputs[1];
    return c;
}

float spread(int i, int n) { return n > 1 ? float(i) / float(n - 1) : 0.0f; }

uint32_t pixelSeed(int x, int y) { return pcgHash(uint32_t(x) + uint32_t(y) * 65521u); }

// Runs `ao(surface, x, y)` for every non-background pixel; background is 1.
template <class Fn>
Result<std::vector<HostImage>> perPixel(const Context& ctx, Fn ao) {
    CAVITY_ASSIGN(const SdfContext c, sdfContext(ctx));
    auto out = makeOutputs(ctx);
    for (int y = 0; y < ctx.frame.size[1]; ++y)
        for (int x = 0; x < ctx.frame.size[0]; ++x) {
            const Surface s = c.at(x, y);
            out[0].at(x, y, 0) = s.background ? 1.0f : ao(c, s, x, y);
        }
    return out;
}

Result<std::vector<HostImage>> sdfClassic(const Context& ctx) {
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius"), k = floatParam(ctx, "strength");
    return perPixel(ctx, [&](const SdfContext& c, const Surface& s, int, int) {
        float occ = 0.0f;
        for (int i = 0; i < n; ++i) {
            const float t = spread(i, n);
            const float h = 0.01f + (R - 0.01f) * t;
            occ += (h - c.map(s.position + s.normal * h)) * std::pow(0.95f, 4.0f * t);
        }
        occ *= 5.0f / float(n);
        return clamp(1.0f - k * occ, 0.0f, 1.0f);
    });
}

Result<std::vector<HostImage>> sdfMultiplicative(const Context& ctx) {
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius"), k = floatParam(ctx, "strength");
    return perPixel(ctx, [&](const SdfContext& c, const Surface& s, int, int) {
        float ao = 1.0f;
        const float exponent = 6.0f / float(n);
        for (int i = 0; i < n; ++i) {
            const float h = R * float(i + 1) / float(n);
            const float d = c.map(s.position + s.normal * h);
            ao *= std::pow(clamp(1.0f - k * std::max(0.0f, h - d) / h, 0.0f, 1.0f), exponent);
        }
        return ao;
    });
}

Result<std::vector<HostImage>> sdfMultiscale(const Context& ctx) {
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius");
    return perPixel(ctx, [&](const SdfContext& c, const Surface& s, int, int) {
        float ao = 1.0f;
        const float exponent = 7.0f / float(n);
        for (int i = 0; i < n; ++i) {
            const float h = R * std::exp2(-6.0f * (1.0f - spread(i, n)));
            ao *= std::pow(clamp(c.map(s.position + s.normal * h) / h, 0.0f, 1.0f), exponent);
        }
        return std::max(0.035f, std::pow(ao, 0.3f));
    });
}

Result<std::vector<HostImage>> sdfJittered(const Context& ctx) {
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius"), k = floatParam(ctx, "strength");
    return perPixel(ctx, [&](const SdfContext& c, const Surface& s, int x, int y) {
        const float u = pixelHash(x, y);
        float occ = 0.0f;
        for (int i = 1; i <= n; ++i) {
            const float j = fract(u + float(i) * 0.618034f);
            const float l = (float(i) + j) * R / float(n);
            occ += (l - c.map(s.position + s.normal * l)) / (1.0f + l);
        }
        return clamp(1.0f - k * occ / float(n), 0.0f, 1.0f);
    });
}

// sdf_ao.glsl's hemisphereDirection: the unit vector at height z and
// azimuth cs, flipped into n's hemisphere; cosTheta its dot with n.
Vec3 hemisphereDirection(float z, Vec2 cs, Vec3 n, float& cosTheta) {
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    Vec3 dir{r * cs.x, r * cs.y, z};
    cosTheta = dot(dir, n);
    if (cosTheta < 0.0f) {
        dir = -dir;
        cosTheta = -cosTheta;
    }
    return dir;
}

Result<std::vector<HostImage>> sdfHemisphere(const Context& ctx) {
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius"), k = floatParam(ctx, "strength");
    return perPixel(ctx, [&](const SdfContext& c, const Surface& s, int x, int y) {
        const uint32_t seed = pixelSeed(x, y);
        float vis = 0.0f;
        for (int i = 0; i < n; ++i) {
            const uint32_t h1 = pcgHash(seed + uint32_t(i));
            const float z = 1.0f - 2.0f * hashToUnit(h1);
            const Vec2 cs = cosSinTurns(hashToUnit(pcgHash(h1)));
            float cosTheta;
            const Vec3 dir = hemisphereDirection(z, cs, s.normal, cosTheta);
            const float t = spread(i, n);
            const float h = 0.01f + R * t * t;
            const float d = c.map(s.position + dir * h);
            vis += clamp(1.0f - k * (h * cosTheta - d) / h, 0.0f, 1.0f);
        }
        return vis / float(n);
    });
}

Result<std::vector<HostImage>> sdfFibonacci(const Context& ctx) {
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius"), k = floatParam(ctx, "strength");
    return perPixel(ctx, [&](const SdfContext& c, const Surface& s, int x, int y) {
        const uint32_t seed = pixelSeed(x, y);
        const Vec3 origin = s.position + s.normal * 0.01f;
        float vis = 0.0f;
        for (int i = 0; i < n; ++i) {
            const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(n);
            const Vec2 cs = cosSinTurns(float(i) * 0.618034f);
            float cosTheta;
            const Vec3 dir = hemisphereDirection(z, cs, s.normal, cosTheta);
            const float dist = R * (0.1f + 0.9f * hashToUnit(pcgHash(seed + uint32_t(i))));
            const float d = c.map(origin + dir * dist);
            vis += clamp(1.0f - k * (0.01f + dist * cosTheta - d) / (0.01f + dist), 0.0f, 1.0f);
        }
        return vis / float(n);
    });
}

// ground_truth.glsl's constants and basis.
const float kGtOffset = 2e-3f, kGtHit = 2e-4f;
const int kGtMaxSteps = 128;

void basisAround(Vec3 n, Vec3& t, Vec3& b) {
    const float sgn = n.z >= 0.0f ? 1.0f : -1.0f;
    const float a = -1.0f / (sgn + n.z);
    const float c = n.x * n.y * a;
    t = {1.0f + sgn * n.x * n.x * a, sgn * c, -sgn * n.x};
    b = {c, sgn + n.y * n.y * a, -n.y};
}

bool blocked(const SdfContext& c, Vec3 o, Vec3 dir, float reach) {
    float t = 0.0f;
    for (int i = 0; i < kGtMaxSteps; ++i) {
        const float d = c.map(o + dir * t);
        if (d < kGtHit) return true;
        t += d;
        if (t >= reach) return false;
    }
    return true;
}

Result<std::vector<HostImage>> sdfGroundTruth(const Context& ctx) {
    const int n = intParam(ctx, "rays");
    const float R = floatParam(ctx, "radius");
    return perPixel(ctx, [&](const SdfContext& c, const Surface& s, int x, int y) {
        Vec3 t, b;
        basisAround(s.normal, t, b);
        const Vec3 origin = s.position + s.normal * kGtOffset;
        const float rotation = pixelHash(x, y);
        int open = 0;
        for (int i = 0; i < n; ++i) {
            const float u = (float(i) + 0.5f) / float(n);
            const Vec2 cs = cosSinTurns(float(i) * 0.618034f + rotation);
            const float r = std::sqrt(u);
            const Vec3 dir = t * (r * cs.x) + b * (r * cs.y) + s.normal * std::sqrt(std::max(0.0f, 1.0f - u));
            if (!blocked(c, origin, dir, R)) ++open;
        }
        return float(open) / float(n);
    });
}

}  // namespace

std::vector<RefEntry> sdfAoRefs() {
    return {
        {"sdf_classic", sdfClassic},       {"sdf_multiplicative", sdfMultiplicative}, {"sdf_multiscale", sdfMultiscale},
        {"sdf_jittered", sdfJittered},     {"sdf_hemisphere", sdfHemisphere},         {"sdf_fibonacci", sdfFibonacci},
        {"ground_truth", sdfGroundTruth},
    };
}

}  // namespace cavity::reference
