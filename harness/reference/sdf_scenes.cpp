// Mirrors kernels/include/sdf_scenes.glsl line for line; the GLSL file says
// why the scenes look as they do.
#include "reference/sdf_scenes.h"

#include <algorithm>
#include <cmath>

namespace cavity::reference {

namespace {

enum Material {
    Floor = 0, WallX = 1, WallZ = 2, Sphere = 3, Slat = 4, Cabinet = 5, Back = 6,
    Table = 7, Cube = 8, Grille = 9, Cavity = 10, Plate = 11
};

float sdBox(Vec3 p, Vec3 center, Vec3 halfSize) {
    const Vec3 q = abs(p - center) - halfSize;
    return length(max(q, 0.0f)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
}

float sdCylinder(Vec3 p, Vec3 center, float radius, float halfHeight) {
    const Vec3 q = p - center;
    const float dx = std::sqrt(q.x * q.x + q.z * q.z) - radius, dy = std::fabs(q.y) - halfHeight;
    const float ox = std::max(dx, 0.0f), oy = std::max(dy, 0.0f);
    return std::min(std::max(dx, dy), 0.0f) + std::sqrt(ox * ox + oy * oy);
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

SceneHit floorScene(Vec3 p) { return {sdBox(p, {0.0f, -0.1f, 0.0f}, {30.0f, 0.1f, 30.0f}), Floor}; }

SceneHit contactScene(Vec3 p) {
    SceneHit h{sdBox(p, {0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 3.0f}), Floor};
    h = nearer(h, {sdBox(p, {0.0f, 0.75f, 0.0f}, {1.0f, 0.03f, 0.6f}), Table});
    const Vec3 leg{std::fabs(p.x), p.y, std::fabs(p.z)};
    h = nearer(h, {sdBox(leg, {0.92f, 0.36f, 0.52f}, {0.04f, 0.36f, 0.04f}), Table});
    h = nearer(h, {length(p - Vec3{-0.35f, 0.98f, 0.1f}) - 0.2f, Sphere});
    h = nearer(h, {sdBox(p, {0.3f, 0.93f, -0.1f}, {0.15f, 0.15f, 0.15f}), Cube});
    return h;
}

const float kGrillePitch = 0.1f;

SceneHit grilleScene(Vec3 p) {
    SceneHit h{sdBox(p, {0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 3.0f}), Floor};
    h = nearer(h, {sdBox(p, {0.0f, 0.1f, -0.14f}, {1.1f, 0.1f, 0.16f}), Cavity});
    h = nearer(h, {sdBox(p, {0.0f, 1.45f, -0.14f}, {1.1f, 0.05f, 0.16f}), Cavity});
    h = nearer(h, {sdBox({std::fabs(p.x), p.y, p.z}, {1.05f, 0.8f, -0.14f}, {0.05f, 0.6f, 0.16f}), Cavity});
    h = nearer(h, {sdBox(p, {0.0f, 0.8f, -0.28f}, {1.0f, 0.6f, 0.02f}), Cavity});
    const float i = std::clamp(std::floor((p.x + 1.0f) / kGrillePitch + 0.5f), 0.0f, 20.0f);
    const float j = std::clamp(std::floor((p.y - 0.2f) / kGrillePitch + 0.5f), 0.0f, 12.0f);
    const Vec3 column{p.x - (-1.0f + i * kGrillePitch), p.y, p.z};
    const Vec3 row{p.x, p.y - (0.2f + j * kGrillePitch), p.z};
    h = nearer(h, {sdBox(column, {0.0f, 0.8f, 0.0f}, {0.015f, 0.6f, 0.015f}), Grille});
    h = nearer(h, {sdBox(row, {0.0f, 0.0f, 0.0f}, {1.0f, 0.015f, 0.015f}), Grille});
    return h;
}

SceneHit platesScene(Vec3 p) {
    SceneHit h{sdBox(p, {0.0f, -0.1f, 0.0f}, {3.0f, 0.1f, 3.0f}), Floor};
    h = nearer(h, {sdCylinder(p, {0.0f, 0.04f, 0.0f}, 0.8f, 0.04f), Plate});
    h = nearer(h, {sdCylinder(p, {0.0f, 0.12f, 0.0f}, 0.72f, 0.04f), Plate});
    h = nearer(h, {sdCylinder(p, {0.0f, 0.2f, 0.0f}, 0.64f, 0.04f), Plate});
    return h;
}

}  // namespace

SceneHit sceneDistance(Scene scene, Vec3 p) {
    switch (scene) {
    case Scene::Slats: return slatsScene(p);
    case Scene::Open: return floorScene(p);
    case Scene::Contact: return contactScene(p);
    case Scene::Grille: return grilleScene(p);
    case Scene::Plates: return platesScene(p);
    default: return cornerScene(p);
    }
}

Vec3 materialAlbedo(int material) {
    auto rgb8 = [](float r, float g, float b) { return Vec3{r / 255.0f, g / 255.0f, b / 255.0f}; };
    switch (material) {
    case Floor: return rgb8(158, 153, 143);
    case WallX: return rgb8(204, 143, 117);
    case WallZ: return rgb8(143, 173, 204);
    case Sphere: return rgb8(235, 235, 230);
    case Slat: return rgb8(194, 148, 102);
    case Cabinet: return rgb8(143, 102, 69);
    case Back: return rgb8(179, 153, 128);
    case Table: return rgb8(150, 110, 80);
    case Cube: return rgb8(120, 160, 200);
    case Grille: return rgb8(170, 170, 175);
    case Cavity: return rgb8(90, 90, 100);
    default: return rgb8(225, 222, 210);
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
    static const CameraPose open[4] = {
        {{0.0f, 1.0f, 3.0f}, {0.0f, 0.0f, 0.0f}},
        {{1.0f, 1.0f, 3.0f}, {0.3f, 0.0f, 0.0f}},
        {{-1.0f, 0.9f, 2.8f}, {-0.3f, 0.0f, 0.0f}},
        {{0.5f, 1.1f, 3.2f}, {0.2f, 0.1f, 0.0f}},
    };
    static const CameraPose contact[4] = {
        {{1.0f, 1.5f, 1.9f}, {0.0f, 0.85f, 0.0f}},
        {{-1.0f, 1.5f, 1.9f}, {0.0f, 0.85f, 0.0f}},
        {{0.3f, 1.4f, 2.0f}, {0.0f, 0.85f, 0.0f}},
        {{1.6f, 1.6f, 1.4f}, {0.0f, 0.85f, 0.0f}},
    };
    static const CameraPose grille[4] = {
        {{0.6f, 1.1f, 2.0f}, {0.0f, 0.8f, 0.0f}},
        {{-0.6f, 1.1f, 2.0f}, {0.0f, 0.8f, 0.0f}},
        {{0.0f, 0.95f, 1.6f}, {0.0f, 0.8f, 0.0f}},
        {{1.2f, 1.2f, 1.8f}, {0.1f, 0.8f, 0.0f}},
    };
    static const CameraPose plates[4] = {
        {{1.3f, 0.75f, 1.5f}, {0.0f, 0.12f, 0.0f}},
        {{-1.3f, 0.75f, 1.5f}, {0.0f, 0.12f, 0.0f}},
        {{0.0f, 0.7f, 1.8f}, {0.0f, 0.12f, 0.0f}},
        {{1.7f, 0.8f, 0.9f}, {0.0f, 0.12f, 0.0f}},
    };
    const int v = std::clamp(view, 0, 3);
    switch (scene) {
    case Scene::Slats: return slats[v];
    case Scene::Open: return open[v];
    case Scene::Contact: return contact[v];
    case Scene::Grille: return grille[v];
    case Scene::Plates: return plates[v];
    default: return corner[v];
    }
}

}  // namespace cavity::reference
