// Mirrors kernels/include/sdf_scenes.glsl line for line; the GLSL file says
// why the scenes look as they do.
#include "sdf_scenes.h"

#include <algorithm>
#include <cmath>

namespace cavity::reference {

namespace {

enum Material { Floor = 0, WallX = 1, WallZ = 2, Sphere = 3, Slat = 4, Cabinet = 5, Back = 6 };

float sdBox(Vec3 p, Vec3 center, Vec3 halfSize) {
    const Vec3 q = abs(p - center) - halfSize;
    return length(max(q, 0.0f)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
}

SceneHit nearer(SceneHit a, SceneHit b) { return b.distance < a.distance ? b : a; }

const Vec3 kSphereCenter{0.8f, 0.5f, 1.6f};
const float kSphereRadius = 0.5f;

SceneHit cornerScene(Vec3 p) {
    SceneHit h{sdBox(p, {1.9f, -0.1f, 1.9f}, {2.1f, 0.1f, 2.1f}), Floor};
    h = nearer(h, {sdBox(p, {-0.1f, 0.9f, 1.9f}, {0.1f, 1.1f, 2.1f}), WallX});
    h = nearer(h, {sdBox(p, {1.9f, 0.9f, -0.1f}, {2.1f, 1.1f, 0.1f}), WallZ});
    h = nearer(h, {length(p - kSphereCenter) - kSphereRadius, Sphere});
    return h;
}

const int kSlatCount = 30;
const float kSlatPitch = 0.12f;

SceneHit slatsScene(Vec3 p) {
    SceneHit h{sdBox(p, {0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 2.5f}), Floor};
    h = nearer(h, {sdBox(p, {0.0f, 0.06f, -0.17f}, {1.86f, 0.06f, 0.23f}), Cabinet});
    h = nearer(h, {sdBox(p, {0.0f, 2.08f, -0.17f}, {1.86f, 0.06f, 0.23f}), Cabinet});
    h = nearer(h, {sdBox(p, {-1.83f, 1.07f, -0.17f}, {0.03f, 1.07f, 0.23f}), Cabinet});
    h = nearer(h, {sdBox(p, {1.83f, 1.07f, -0.17f}, {0.03f, 1.07f, 0.23f}), Cabinet});
    h = nearer(h, {sdBox(p, {0.0f, 1.07f, -0.37f}, {1.80f, 0.95f, 0.03f}), Back});
    const float cell = std::clamp(std::floor(p.x / kSlatPitch), -float(kSlatCount / 2), float(kSlatCount / 2 - 1));
    const Vec3 local{p.x - (cell + 0.5f) * kSlatPitch, p.y, p.z};
    h = nearer(h, {sdBox(local, {0.0f, 1.07f, -0.09f}, {0.025f, 0.95f, 0.09f}), Slat});
    return h;
}

}  // namespace

SceneHit sceneDistance(Scene scene, Vec3 p) { return scene == Scene::Slats ? slatsScene(p) : cornerScene(p); }

Vec3 materialAlbedo(int material) {
    auto rgb8 = [](float r, float g, float b) { return Vec3{r / 255.0f, g / 255.0f, b / 255.0f}; };
    switch (material) {
    case Floor: return rgb8(158, 153, 143);
    case WallX: return rgb8(204, 143, 117);
    case WallZ: return rgb8(143, 173, 204);
    case Sphere: return rgb8(235, 235, 230);
    case Slat: return rgb8(194, 148, 102);
    case Cabinet: return rgb8(143, 102, 69);
    default: return rgb8(179, 153, 128);
    }
}

CameraPose sceneCamera(Scene scene, int view) {
    static const CameraPose corner[4] = {
        {{2.7f, 1.3f, 2.8f}, {0.5f, 0.45f, 0.6f}},
        {{3.1f, 1.25f, 2.1f}, {0.6f, 0.45f, 0.7f}},
        {{2.0f, 1.25f, 3.2f}, {0.5f, 0.45f, 0.8f}},
        {{2.5f, 1.1f, 2.5f}, {0.45f, 0.4f, 0.55f}},
    };
    static const CameraPose slats[4] = {
        {{0.72f, 1.25f, 2.3f}, {0.05f, 1.0f, -0.1f}},
        {{-0.72f, 1.25f, 2.3f}, {-0.05f, 1.0f, -0.1f}},
        {{0.36f, 1.05f, 2.2f}, {0.0f, 1.0f, -0.1f}},
        {{1.08f, 1.5f, 2.25f}, {0.1f, 1.0f, -0.1f}},
    };
    const int v = std::clamp(view, 0, 3);
    return scene == Scene::Slats ? slats[v] : corner[v];
}

}  // namespace cavity::reference
