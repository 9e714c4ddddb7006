// The CPU side of kernels/include/sdf_scenes.glsl: the same scenes, cameras
// and materials, for the G-buffer reference.
#pragma once

#include "reference/namespace.h"
#include "reference/vec.h"

namespace cavity::reference {

enum class Scene { Corner = 0, Slats = 1, Open = 2, Contact = 3, Grille = 4, Plates = 5 };
constexpr int kSceneCount = 6;

struct SceneHit {
    float distance;
    int material;
};

SceneHit sceneDistance(Scene scene, Vec3 p);
Vec3 materialAlbedo(int material);

struct CameraPose {
    Vec3 eye, target;
};
CameraPose sceneCamera(Scene scene, int view);

}  // namespace cavity::reference
