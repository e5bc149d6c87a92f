// How far light travels between surfaces in a scene: the mean free path of rays leaving its
// surfaces, measured on a coarse occupancy grid (no BVH, so gi_core needs no ray tracer).
//
// Why: a technique on a grid carries light a limited number of cells. LPV's propagation loses
// most of a beam's flux to the side faces at every step, so light crosses about ten to fifteen
// cells, whatever the step count: in a Cornell box on a 32^3 grid the ceiling, 31 cells above
// the lit floor, stays black even after 96 steps, and on 16^3 it is lit. A scene's grid should
// therefore span its typical free path in a bounded number of cells (gi/lpv/lpv.h, "Fitted grid").
//
// Method (deterministic): the scene's grid cube (Bounds::gridCubeSize(), as the techniques' grids) is
// cut into kFreePathGrid^3 cells, and every cell a triangle touches is marked (points on each
// triangle at most half a cell apart). kFreePathRays rays then leave points on the surfaces,
// chosen by area, on a random side, with cosine-distributed directions, and march the cells
// (3D DDA) from 1.5 cells above their own surface until an occupied cell or the cube's boundary.
// The mean of the distances from the surface points to where the rays stop, in world units (the
// occupancy stops a ray up to a cell before the surface it meets). A ray that leaves the cube counts its distance to
// the boundary, so an open scene's free path is about its size.
#pragma once

#include "gi/scene/scene.h"

namespace gi {

constexpr int kFreePathGrid = 64;
constexpr int kFreePathRays = 4096;
// The most points the occupancy marks (Crytek Sponza, 262k triangles: 2.0 million), so no scene
// takes long (a budget of points takes about 0.3 s here).
constexpr size_t kFreePathPointBudget = size_t(1) << 25;

struct FreePath {
    float meanDistance = 0.0f;  // world units
    float cubeSize = 0.0f;      // the side of the bounding cube the rays marched in
    int rays = 0;               // rays traced (0 for a scene without surface area)
    float hitFraction = 0.0f;   // of those, the share that met a surface before the boundary
    float meanHitDistance = 0.0f;  // the mean over those that met a surface
    size_t points = 0;             // points marked in the occupancy (work: the budget and at most one triangle's more)
};

FreePath meanFreePath(const Scene& scene);

}  // namespace gi
