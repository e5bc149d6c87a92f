// Emissive surfaces as area lights: the grouping of a scene's emissive triangles (Scene::emitters).
#pragma once

#include "gi/scene/scene.h"

namespace gi {

// Groups the emissive triangles of `scene` into scene.emitters and fills scene.triangleEmitter:
// triangles of one material that share a vertex position are one surface; a surface of more
// than kMaxEmitterTriangles triangles is split at the median of its triangles' centres along its
// longest side until each part fits. Past kMaxEmitters the faintest are dropped with a warning
// (their triangles then emit nothing anywhere).
void buildEmitters(Scene& scene);

// Emitters that cast shadows by default (sceneLights): the most powerful ones.
inline constexpr int kShadowedEmitters = 4;

// Area light l placed on its emitter: the position is the centroid (where its cube shadow map and
// the passes that see it as a point stand), the direction the mean normal.
LightSettings placeAreaLight(LightSettings l, const Emitter& e);

}  // namespace gi
