// The signed-distance scenes as triangle meshes, for the rasterised G-buffer:
// the same boxes, spheres and cylinders as kernels/include/sdf_scenes.glsl, built in C++
// (no asset files) and transformed into the view space of a camera view.
#pragma once

#include "pipeline/namespace.h"
#include <vector>

namespace cavity::pipeline {

// One vertex: view-space position, view-space normal, albedo; three vec4s,
// the layout the raster kernel reads from its storage buffer (std430).
struct MeshVertex {
    float position[4];   // xyz, w unused
    float normal[4];
    float albedo[4];
};

// Triangles (3 vertices each) of scene `scene` (the index of a --scene
// choice: corner, slats, open, contact, grille, plates) seen from camera
// view `view` (0..3). Empty for an index that names no scene.
std::vector<MeshVertex> sceneMesh(int scene, int view);

}  // namespace cavity::pipeline