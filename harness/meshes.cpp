#include "meshes.h"

#include "sdf_scenes.h"

#include <cmath>

namespace cavity {

namespace {

using reference::Vec3;

struct Builder {
    Vec3 eye, right, up, forward;
    std::vector<MeshVertex> out;

    MeshVertex vertex(Vec3 p, Vec3 n, Vec3 albedo) const {
        const Vec3 q = p - eye;
        return {{dot(q, right), dot(q, up), -dot(q, forward), 1.0f},
                {dot(n, right), dot(n, up), -dot(n, forward), 0.0f},
                {albedo.x, albedo.y, albedo.z, 1.0f}};
    }
    void triangle(Vec3 a, Vec3 b, Vec3 c, Vec3 na, Vec3 nb, Vec3 nc, Vec3 albedo) {
        out.push_back(vertex(a, na, albedo));
        out.push_back(vertex(b, nb, albedo));
        out.push_back(vertex(c, nc, albedo));
    }
    // An axis-aligned box as 12 flat-shaded triangles (no culling, so the
    // winding does not matter).
    void box(Vec3 c, Vec3 h, Vec3 albedo) {
        const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        const float hs[3] = {h.x, h.y, h.z};
        for (int a = 0; a < 3; ++a)
            for (float s : {-1.0f, 1.0f}) {
                const Vec3 n = axes[a] * s;
                const Vec3 u = axes[(a + 1) % 3] * hs[(a + 1) % 3], v = axes[(a + 2) % 3] * hs[(a + 2) % 3];
                const Vec3 f = c + n * hs[a];
                triangle(f - u - v, f + u - v, f + u + v, n, n, n, albedo);
                triangle(f - u - v, f + u + v, f - u + v, n, n, n, albedo);
            }
    }
    // A UV sphere with smooth (analytic) normals; 96 x 48 segments keep the
    // chord error under 3e-4 of the radius.
    void sphere(Vec3 c, float r, Vec3 albedo) {
        const int nu = 96, nv = 48;
        auto at = [&](int i, int j) {
            const float phi = 2.0f * float(M_PI) * float(i) / float(nu), theta = float(M_PI) * float(j) / float(nv);
            return Vec3{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
        };
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const Vec3 a = at(i, j), b = at(i + 1, j), cc = at(i + 1, j + 1), d = at(i, j + 1);
                triangle(c + a * r, c + b * r, c + cc * r, a, b, cc, albedo);
                triangle(c + a * r, c + cc * r, c + d * r, a, cc, d, albedo);
            }
    }
};

}  // namespace

std::vector<MeshVertex> sceneMesh(int scene, int view) {
    if (scene != 0 && scene != 1) return {};
    const auto s = scene == 1 ? reference::Scene::Slats : reference::Scene::Corner;
    const auto pose = reference::sceneCamera(s, view);
    Builder b;
    b.eye = pose.eye;
    b.forward = normalize(pose.target - pose.eye);
    b.right = normalize(cross(b.forward, Vec3{0, 1, 0}));
    b.up = cross(b.right, b.forward);
    auto albedo = reference::materialAlbedo;
    // The boxes and sphere of sdf_scenes.cpp, material by material.
    if (s == reference::Scene::Corner) {
        b.box({1.9f, -0.1f, 1.9f}, {2.1f, 0.1f, 2.1f}, albedo(0));
        b.box({-0.1f, 0.9f, 1.9f}, {0.1f, 1.1f, 2.1f}, albedo(1));
        b.box({1.9f, 0.9f, -0.1f}, {2.1f, 1.1f, 0.1f}, albedo(2));
        b.sphere({0.8f, 0.5f, 1.6f}, 0.5f, albedo(3));
    } else {
        b.box({0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 2.5f}, albedo(0));
        b.box({0.0f, 0.06f, -0.17f}, {1.86f, 0.06f, 0.23f}, albedo(5));
        b.box({0.0f, 2.08f, -0.17f}, {1.86f, 0.06f, 0.23f}, albedo(5));
        b.box({-1.83f, 1.07f, -0.17f}, {0.03f, 1.07f, 0.23f}, albedo(5));
        b.box({1.83f, 1.07f, -0.17f}, {0.03f, 1.07f, 0.23f}, albedo(5));
        b.box({0.0f, 1.07f, -0.37f}, {1.80f, 0.95f, 0.03f}, albedo(6));
        for (int i = 0; i < 30; ++i)
            b.box({(float(i - 15) + 0.5f) * 0.12f, 1.07f, -0.09f}, {0.025f, 0.95f, 0.09f}, albedo(4));
    }
    return b.out;
}

}  // namespace cavity
