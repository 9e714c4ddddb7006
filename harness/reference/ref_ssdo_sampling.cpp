// The SSDO references' shared sampling and sky (reference/ssdo.h), mirroring
// include/ssdo.glsl, ssdo_sampling.glsl, ssdo_fast.glsl and sky.glsl.
#include "families.h"
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/pyramid.h"
#include "reference/ssdo.h"

#include <algorithm>
#include <cmath>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
float inverseSqrt(float x);
Vec3 normalizeExact(Vec3 v);
bool texelOfView(const kernels::FrameUniforms& f, Vec3 p, int& tx, int& ty);
bool texelInside(const kernels::FrameUniforms& f, int tx, int ty);
float sampleHash(int x, int y, int i);
Vec3 texel3(const HostImage& img, int x, int y);
}  // namespace screen

namespace ssdo {

namespace {

float portableAtan2(float y, float x) {
    const float ax = std::fabs(x), ay = std::fabs(y);
    const float hi = std::max(ax, ay), lo = std::min(ax, ay);
    if (hi == 0.0f) return 0.0f;
    const float a = lo * portableReciprocal(hi);
    const float a2 = a * a;
    float r = a * (0.99997726f + a2 * (-0.33262347f + a2 * (0.19354346f + a2 * (-0.11643287f + a2 * (0.05265332f + a2 * -0.01172120f)))));
    if (ay > ax) r = 1.5707964f - r;
    if (x < 0.0f) r = 3.1415927f - r;
    return y < 0.0f ? -r : r;
}

Vec3 bilinear(const kernels::ConstantImageDecl::Level& l, Vec2 uv) {
    const float x = uv.x * float(l.width) - 0.5f, y = uv.y * float(l.height) - 0.5f;
    const float x0f = std::floor(x), y0f = std::floor(y);
    const float ax = x - x0f, ay = y - y0f;
    const int x0 = std::clamp(int(x0f), 0, l.width - 1), x1 = std::clamp(int(x0f) + 1, 0, l.width - 1);
    const int y0 = std::clamp(int(y0f), 0, l.height - 1), y1 = std::clamp(int(y0f) + 1, 0, l.height - 1);
    auto at = [&](int tx, int ty) {
        const float* p = &l.pixels[(size_t(ty) * l.width + tx) * 4];
        return Vec3{p[0], p[1], p[2]};
    };
    return mix(mix(at(x0, y0), at(x1, y0), ax), mix(at(x0, y1), at(x1, y1), ax), ay);
}

float skyLuminance(Vec3 c) { return dot(c, Vec3{0.2126f, 0.7152f, 0.0722f}); }

Vec3 ssdoDirection(const Basis& f, int i, int count) {
    const float alpha = (float(i) + 0.5f) * portableReciprocal(float(count));
    const float cosE = 1.0f - alpha;
    const float sin2 = 1.0f - cosE * cosE;
    const float sinE = sin2 * screen::inverseSqrt(sin2);
    const float turns = (float(i) + 0.5f) * 0.7777778f + f.phiTurns;
    const Vec2 cs = cosSinTurns(turns);
    return f.t * (sinE * cs.x) + f.b * (sinE * cs.y) + f.n * cosE;
}

bool ssdoBlocked(const kernels::FrameUniforms& fr, const HostImage& position, const HostImage& normal, const Basis& f,
                 Vec3 p, Vec3 point, float bias, int& tx, int& ty) {
    if (!screen::texelOfView(fr, point, tx, ty) || !screen::texelInside(fr, tx, ty)) return false;
    const Vec3 q = screen::texel3(position, tx, ty);
    const Vec3 m = screen::texel3(normal, tx, ty);
    if (isBackground(position.at(tx, ty, 3)) || lengthSquared(m) == 0.0f) return false;
    // Only a recorded point above the receiver's tangent plane occludes (see ssdo.glsl).
    if (dot(f.n, q - p) <= 0.0f) return false;
    if (dot(m, q) < 0.0f) return dot(m, point - q) < -bias;
    const float reach = lengthSquared(q);
    const float limit = reach * screen::inverseSqrt(reach) + bias;
    return lengthSquared(point) > limit * limit;
}

}  // namespace

const Levels* skyLevels() {
    static const Levels levels = [] {
        for (const auto& c : kernels::screenSpaceConstants())
            if (c.name == "sky") return c.make({});
        return Levels{};
    }();
    return levels.empty() ? nullptr : &levels;
}

Vec2 skyUv(Vec3 d) {
    const float u = portableAtan2(d.x, d.z) * 0.15915494f + 0.5f;
    const float s2 = std::max(1.0f - d.y * d.y, 0.0f);
    const float s = s2 > 0.0f ? s2 * screen::inverseSqrt(s2) : 0.0f;
    const float v = portableAtan2(s, d.y) * 0.31830987f;
    return {u, v};
}

// textureLod(sky, uv, lod) with a linear, mip-linear, clamp-to-edge sampler.
Vec3 sampleSky(const Levels& levels, Vec2 uv, float lod) {
    lod = clamp(lod, 0.0f, float(levels.size() - 1));
    const int l0 = int(std::floor(lod));
    const float a = lod - float(l0);
    const Vec3 c0 = bilinear(levels[size_t(l0)], uv);
    if (a == 0.0f) return c0;
    const int l1 = std::min(l0 + 1, int(levels.size()) - 1);
    return mix(c0, bilinear(levels[size_t(l1)], uv), a);
}

Vec3 skyAmbient(const std::vector<float>& sh, Vec3 n) {
    auto c = [&](int k) { return Vec3{sh[size_t(k) * 4], sh[size_t(k) * 4 + 1], sh[size_t(k) * 4 + 2]}; };
    Vec3 e = c(0);
    e = e + c(1) * n.y;
    e = e + c(2) * n.z;
    e = e + c(3) * n.x;
    e = e + c(4) * (n.x * n.y);
    e = e + c(5) * (n.y * n.z);
    e = e + c(6) * (3.0f * n.z * n.z - 1.0f);
    e = e + c(7) * (n.x * n.z);
    e = e + c(8) * (n.x * n.x - n.y * n.y);
    return max(e, 0.0f);
}

Basis ssdoBasis(int x, int y, Vec3 n) {
    const Vec3 up = std::fabs(n.y) < 0.999f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    Basis f;
    f.n = n;
    f.t = screen::normalizeExact(cross(up, n));
    f.b = cross(n, f.t);
    f.phiTurns = 0.5f * ign(float(x) + 0.5f, float(y) + 0.5f);
    return f;
}

// Direction i marched in `steps` points (1: seed 003's one random length).
Sample ssdoSample(const kernels::FrameUniforms& fr, const HostImage& position, const HostImage& normal, const Basis& f,
                  Vec3 p, int x, int y, int i, int count, int steps, float radius, float bias) {
    Sample s;
    s.dir = ssdoDirection(f, i, count);
    const float u = screen::sampleHash(x, y, i);
    const float perStep = portableReciprocal(float(steps));
    for (int j = 0; j < steps; ++j) {
        const float lambda = radius * ((float(j + 1) - u) * perStep);
        const Vec3 point = p + s.dir * lambda;
        int tx = -1, ty = -1;
        if (ssdoBlocked(fr, position, normal, f, p, point, bias, tx, ty)) {
            s.visible = false;
            s.tx = tx, s.ty = ty;
            return s;
        }
    }
    return s;
}

void SkyGather::add(Vec3 n, Vec3 dir, Vec3 sky, bool open) {
    const float cosTheta = std::max(dot(n, dir), 0.0f);
    const float weight = skyLuminance(sky) * cosTheta;
    total += weight;
    if (open) {
        visible += weight;
        direct = direct + sky * cosTheta;
    }
}

float SkyGather::visibility(float contrast) const {
    const float v = total > 0.0f ? visible / total : 1.0f;
    return clamp(std::pow(v, contrast), 0.0f, 1.0f);
}

Vec3 SkyGather::radiance(int count) const { return direct * (2.0f / float(count)); }

// bounceFrom() of include/ssdo_sampling.glsl.
Vec3 bounceFrom(Vec3 p, Vec3 n, Vec3 q, Vec3 m, Vec3 emitted, float radius, float distanceClamp) {
    const Vec3 toSender = q - p;
    const float dist = length(toSender);
    if (dist <= 0.0f) return {};
    const Vec3 w = toSender * (1.0f / dist);
    const float cosSender = std::max(dot(m, -w), 0.0f);
    const float cosReceiver = std::max(dot(n, w), 0.0f);
    const float falloff = std::max(1.0f - dist / radius, 0.0f);
    const float d = std::max(distanceClamp, dist);
    return emitted * (cosSender * cosReceiver * falloff / (d * d));
}

FastMarch::FastMarch(const Context& ctx)
    : f(ctx.frame), zmip(pyramidLevels(*ctx.inputs[0], pyramid::levelCount())), normal(*ctx.inputs[1]),
      view(pyramid::view(f, int(zmip.size()))), n(std::clamp(intParam(ctx, "samples"), 1, 256)),
      steps(std::clamp(intParam(ctx, "steps"), 1, 16)), radius(floatParam(ctx, "radius")),
      bias(floatParam(ctx, "bias")) {}

bool FastMarch::receiver(int x, int y, Receiver& r) const {
    r.depth = zmip[0].at(x, y);
    const Vec3 nrm = screen::texel3(normal, x, y);
    if (isBackground(r.depth) || lengthSquared(nrm) == 0.0f) return false;
    r.n = screen::normalizeExact(nrm);
    r.X = pyramid::positionAt(f, x, y, r.depth);
    r.level = dot(r.n, r.X);
    r.basis = ssdoBasis(x, y, r.n);
    return true;
}

Sample FastMarch::sample(const Receiver& r, int x, int y, int i, float& senderDepth) const {
    Sample s;
    s.dir = ssdoDirection(r.basis, i, n);
    senderDepth = 0.0f;
    const float u = screen::sampleHash(x, y, i);
    const float perStep = portableReciprocal(float(steps));
    for (int j = 0; j < steps; ++j) {
        const float lambda = radius * ((float(j + 1) - u) * perStep);
        const Vec3 point = r.X + s.dir * lambda;
        if (pyramid::blocks(f, zmip, view, r.n, r.level, point, x, y, bias, s.tx, s.ty, senderDepth)) {
            s.visible = false;
            return s;
        }
    }
    s.tx = s.ty = -1;
    senderDepth = 0.0f;
    return s;
}

Vec3 viewRay(const kernels::FrameUniforms& f, int x, int y) {
    const float ndcX = (float(x) + 0.5f) * f.invSize[0] * 2.0f - 1.0f;
    const float ndcY = (float(y) + 0.5f) * f.invSize[1] * 2.0f - 1.0f;
    return {ndcX * f.camera[0], -ndcY * f.camera[1], -1.0f};
}

void put(HostImage& img, int x, int y, Vec3 c, float a) {
    img.at(x, y, 0) = c.x, img.at(x, y, 1) = c.y, img.at(x, y, 2) = c.z, img.at(x, y, 3) = a;
}

}  // namespace ssdo
}  // namespace cavity::reference
