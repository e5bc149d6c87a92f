// One light of a batch for the compute passes that light voxels or the medium (VCT injection,
// the volumetric march): their shaders declare the same arrays, uLightType[], uLightColor[]
// (color * intensity), uLightPos[], uLightDir[] (unit, the way the light travels), uLightRange[],
// uLightCos[] (cos inner, cos outer), uShadowed[], uShadowViewProj[], uShadowFar[].
#pragma once

#include "gi/gl/shader.h"
#include "gi/render/pass.h"
#include "gi/scene/scene_settings.h"

namespace gi {

// Sets entry i of those arrays for light l and binds its shadow map (when it has one) to unit
// unit2D + i or unitCube + i, as its type needs; samplers are the caller's.
void setLightBatchUniforms(const gl::Program& p, int i, const LightSettings& l, const ShadowMapView& sm, GLuint unit2D,
                           GLuint unitCube);

}  // namespace gi
