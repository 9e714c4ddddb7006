#include "pipeline/meshes.h"

#include "reference/sdf_scenes.h"

#include <cmath>

namespace cavity::pipeline {

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
    // A vertical cylinder (axis +Y) with flat caps: 96 side quads with
    // smooth normals and two fans with flat ones.
    void cylinder(Vec3 c, float r, float halfHeight, Vec3 albedo) {
        const int nu = 96;
        const Vec3 up{0, 1, 0}, down{0, -1, 0};
        auto rim = [&](int i) {
            const float phi = 2.0f * float(M_PI) * float(i) / float(nu);
            return Vec3{std::cos(phi), 0.0f, std::sin(phi)};
        };
        const Vec3 top = c + up * halfHeight, bottom = c + down * halfHeight;
        for (int i = 0; i < nu; ++i) {
            const Vec3 a = rim(i), b = rim(i + 1);
            triangle(bottom + a * r, bottom + b * r, top + b * r, a, b, b, albedo);
            triangle(bottom + a * r, top + b * r, top + a * r, a, b, a, albedo);
            triangle(top, top + a * r, top + b * r, up, up, up, albedo);
            triangle(bottom, bottom + b * r, bottom + a * r, down, down, down, albedo);
        }
    }
};

}  // namespace

std::vector<MeshVertex> sceneMesh(int scene, int view) {
    if (scene < 0 || scene >= reference::kSceneCount) return {};
    const auto s = reference::Scene(scene);
    const auto pose = reference::sceneCamera(s, view);
    Builder b;
    b.eye = pose.eye;
    b.forward = normalize(pose.target - pose.eye);
    b.right = normalize(cross(b.forward, Vec3{0, 1, 0}));
    b.up = cross(b.right, b.forward);
    auto albedo = reference::materialAlbedo;
    // The boxes and sphere of sdf_scenes.cpp, material by material.
    switch (s) {
    case reference::Scene::Corner:
        b.box({1.9f, -0.1f, 1.9f}, {2.1f, 0.1f, 2.1f}, albedo(0));
        b.box({-0.1f, 0.9f, 1.9f}, {0.1f, 1.1f, 2.1f}, albedo(1));
        b.box({1.9f, 0.9f, -0.1f}, {2.1f, 1.1f, 0.1f}, albedo(2));
        b.sphere({0.8f, 0.5f, 1.6f}, 0.5f, albedo(3));
        break;
    case reference::Scene::Slats:
        b.box({0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 2.5f}, albedo(0));
        b.box({0.0f, 0.06f, -0.17f}, {1.86f, 0.06f, 0.23f}, albedo(5));
        b.box({0.0f, 2.08f, -0.17f}, {1.86f, 0.06f, 0.23f}, albedo(5));
        b.box({-1.83f, 1.07f, -0.17f}, {0.03f, 1.07f, 0.23f}, albedo(5));
        b.box({1.83f, 1.07f, -0.17f}, {0.03f, 1.07f, 0.23f}, albedo(5));
        b.box({0.0f, 1.07f, -0.37f}, {1.80f, 0.95f, 0.03f}, albedo(6));
        for (int i = 0; i < 30; ++i)
            b.box({(float(i - 15) + 0.5f) * 0.12f, 1.07f, -0.09f}, {0.025f, 0.95f, 0.09f}, albedo(4));
        break;
    case reference::Scene::Open:
        b.box({0.0f, -0.1f, 0.0f}, {30.0f, 0.1f, 30.0f}, albedo(0));
        break;
    case reference::Scene::Contact:
        b.box({0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 3.0f}, albedo(0));
        b.box({0.0f, 0.75f, 0.0f}, {1.0f, 0.03f, 0.6f}, albedo(7));
        for (float sx : {-1.0f, 1.0f})
            for (float sz : {-1.0f, 1.0f}) b.box({0.92f * sx, 0.36f, 0.52f * sz}, {0.04f, 0.36f, 0.04f}, albedo(7));
        b.sphere({-0.35f, 0.98f, 0.1f}, 0.2f, albedo(3));
        b.box({0.3f, 0.93f, -0.1f}, {0.15f, 0.15f, 0.15f}, albedo(8));
        break;
    case reference::Scene::Grille:
        b.box({0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 3.0f}, albedo(0));
        b.box({0.0f, 0.1f, -0.14f}, {1.1f, 0.1f, 0.16f}, albedo(10));
        b.box({0.0f, 1.45f, -0.14f}, {1.1f, 0.05f, 0.16f}, albedo(10));
        b.box({-1.05f, 0.8f, -0.14f}, {0.05f, 0.6f, 0.16f}, albedo(10));
        b.box({1.05f, 0.8f, -0.14f}, {0.05f, 0.6f, 0.16f}, albedo(10));
        b.box({0.0f, 0.8f, -0.28f}, {1.0f, 0.6f, 0.02f}, albedo(10));
        for (int i = 0; i <= 20; ++i) b.box({-1.0f + 0.1f * float(i), 0.8f, 0.0f}, {0.015f, 0.6f, 0.015f}, albedo(9));
        for (int j = 0; j <= 12; ++j) b.box({0.0f, 0.2f + 0.1f * float(j), 0.0f}, {1.0f, 0.015f, 0.015f}, albedo(9));
        break;
    case reference::Scene::Plates:
        b.box({0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 3.0f}, albedo(0));
        b.cylinder({0.0f, 0.04f, 0.0f}, 0.8f, 0.04f, albedo(11));
        b.cylinder({0.0f, 0.12f, 0.0f}, 0.72f, 0.04f, albedo(11));
        b.cylinder({0.0f, 0.2f, 0.0f}, 0.64f, 0.04f, albedo(11));
        break;
    }
    return b.out;
}

}  // namespace cavity::pipeline