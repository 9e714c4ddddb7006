#include "harness_names.h"
#include "analytic_scenes.h"

#include "core/camera.h"

#include <cmath>
#include <limits>

namespace cavity::test::analytic {

using namespace cavity::harness;

namespace {

constexpr double kPi = 3.14159265358979323846;

V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 normalize(V3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }

// The camera's world-space axes: right, up, forward (view -Z).
struct Basis {
    V3 right, up, forward;
};

Basis cameraBasis(const Camera& c) {
    Basis b;
    b.forward = normalize(c.target - c.eye);
    V3 worldUp{0, 1, 0};
    if (std::fabs(dot(worldUp, b.forward)) > 0.999) worldUp = {0, 0, -1};
    const V3 r = normalize(cross(b.forward, worldUp));
    const V3 u = cross(r, b.forward);
    const double a = c.rollDegrees * kPi / 180.0;
    b.right = r * std::cos(a) + u * std::sin(a);
    b.up = u * std::cos(a) - r * std::sin(a);
    return b;
}

// Slab test: the entry distance of the ray o + t d into the box, in (tMin,
// tMax), and the face it enters through.
bool intersect(const Box& box, V3 o, V3 d, double tMin, double tMax, double& t, V3& normal) {
    const double lo[3] = {box.lo.x, box.lo.y, box.lo.z}, hi[3] = {box.hi.x, box.hi.y, box.hi.z};
    const double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
    int axis = -1;
    double sign = 0;
    for (int i = 0; i < 3; ++i) {
        if (std::fabs(dd[i]) < 1e-300) {
            if (oo[i] < lo[i] || oo[i] > hi[i]) return false;
            continue;
        }
        double t0 = (lo[i] - oo[i]) / dd[i], t1 = (hi[i] - oo[i]) / dd[i];
        double s = -1;   // entering through the lo face: normal -axis
        if (t0 > t1) std::swap(t0, t1), s = 1;
        if (t0 > enter) enter = t0, axis = i, sign = s;
        leave = std::min(leave, t1);
    }
    if (enter > leave || axis < 0 || enter <= tMin || enter >= tMax) return false;
    t = enter;
    normal = {axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0};
    return true;
}

bool firstHit(const Scene& s, V3 o, V3 d, double tMax, double& t, V3& normal) {
    bool any = false;
    t = tMax;
    for (const auto& b : s.boxes) {
        double tb;
        V3 nb;
        if (intersect(b, o, d, 0.0, t, tb, nb)) t = tb, normal = nb, any = true;
    }
    return any;
}

// The i-th of n cosine-weighted directions around n on a Fibonacci lattice,
// turned by `turns` in azimuth.
V3 lattice(V3 n, int i, int count, double turns) {
    const V3 helper = std::fabs(n.x) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0};
    const V3 t = normalize(cross(helper, n)), b = cross(n, t);
    const double u = (i + 0.5) / count;
    const double a = 2 * kPi * (i * 0.6180339887498949 + turns);
    const double r = std::sqrt(u);
    return t * (r * std::cos(a)) + b * (r * std::sin(a)) + n * std::sqrt(std::max(0.0, 1.0 - u));
}

double hash01(int x, int y) {
    uint32_t h = uint32_t(x) * 0x8da6b343u ^ uint32_t(y) * 0xd8163841u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return double(h & 0xffffff) / 16777216.0;
}

}  // namespace

Frame render(const Scene& scene, int width, int height, double reach, int rays) {
    Frame f;
    f.width = width;
    f.height = height;
    f.hits.resize(size_t(width) * height);
    f.gbuffer.position = HostImage(width, height, 4);
    f.gbuffer.normal = HostImage(width, height, 4);
    f.gbuffer.albedo = HostImage(width, height, 4);
    f.truth = HostImage(width, height, 1, 1.0f);
    const Basis cam = cameraBasis(scene.camera);
    const double tanHalf = std::tan(kFovYDegrees * 0.5 * kPi / 180.0), aspect = double(width) / height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double nx = (x + 0.5) / width * 2 - 1, ny = (y + 0.5) / height * 2 - 1;
            const V3 d = normalize(cam.right * (nx * tanHalf * aspect) + cam.up * (-ny * tanHalf) + cam.forward);
            double t;
            V3 n;
            if (!firstHit(scene, scene.camera.eye, d, 1e9, t, n)) continue;
            const V3 w = scene.camera.eye + d * t;
            const V3 rel = w - scene.camera.eye;
            const V3 view{dot(rel, cam.right), dot(rel, cam.up), -dot(rel, cam.forward)};
            if (-view.z < kNear || -view.z > kFar) continue;
            Hit& h = f.hits[size_t(y) * width + x];
            h.surface = true;
            h.world = w;
            h.normal = n;
            const V3 vn{dot(n, cam.right), dot(n, cam.up), -dot(n, cam.forward)};
            const float p[4] = {float(view.x), float(view.y), float(view.z), float(-view.z)};
            const float q[4] = {float(vn.x), float(vn.y), float(vn.z), 0.0f};
            for (int c = 0; c < 4; ++c) {
                f.gbuffer.position.at(x, y, c) = p[c];
                f.gbuffer.normal.at(x, y, c) = q[c];
                f.gbuffer.albedo.at(x, y, c) = c < 3 ? 0.7f : 1.0f;
            }
            // The truth: rays from just above the surface, blocked by any box
            // within the reach.
            const V3 origin = w + n * 1e-7;
            const double turns = hash01(x, y);
            int open = 0;
            for (int i = 0; i < rays; ++i) {
                double tb;
                V3 nb;
                if (!firstHit(scene, origin, lattice(n, i, rays, turns), reach, tb, nb)) ++open;
            }
            f.truth.at(x, y) = float(double(open) / rays);
        }
    return f;
}

double singleLayerVisibility(const Frame& f, int x, int y, double reach, int rays, int steps) {
    const HostImage& pos = f.gbuffer.position;
    const HostImage& nrm = f.gbuffer.normal;
    if (pos.at(x, y, 3) <= 0) return 1.0;
    const V3 p{pos.at(x, y, 0), pos.at(x, y, 1), pos.at(x, y, 2)};
    const V3 n{nrm.at(x, y, 0), nrm.at(x, y, 1), nrm.at(x, y, 2)};
    const double tanHalf = std::tan(kFovYDegrees * 0.5 * kPi / 180.0), aspect = double(f.width) / f.height;
    int open = 0;
    for (int i = 0; i < rays; ++i) {
        const V3 d = lattice(n, i, rays, hash01(x, y));
        bool blocked = false;
        for (int k = 1; k <= steps && !blocked; ++k) {
            const V3 s = p + d * (reach * k / steps);
            if (s.z >= -kNear) break;
            const double sx = (s.x / (-s.z * tanHalf * aspect) + 1) * 0.5 * f.width;
            const double sy = (1 - s.y / (-s.z * tanHalf)) * 0.5 * f.height;
            const int tx = int(std::floor(sx)), ty = int(std::floor(sy));
            if (tx < 0 || ty < 0 || tx >= f.width || ty >= f.height) continue;
            if (pos.at(tx, ty, 3) <= 0) continue;
            const V3 q{pos.at(tx, ty, 0), pos.at(tx, ty, 1), pos.at(tx, ty, 2)};
            const V3 m{nrm.at(tx, ty, 0), nrm.at(tx, ty, 1), nrm.at(tx, ty, 2)};
            // Behind the recorded surface's plane by more than G-buffer
            // rounding: the one layer says solid there.
            blocked = dot(m, s - q) < -1e-4;
        }
        if (!blocked) ++open;
    }
    return double(open) / rays;
}

}  // namespace cavity::test::analytic
