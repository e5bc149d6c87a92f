// The frame's lights as every pass reads them: each LightSettings packed into a light::GPULight
// (the light model, shaders/common/light.h) with its shadow projection, uploaded once per frame
// into one shader storage buffer bound at light::kLightBufferBinding. Passes index it (the raster
// light pass, the RSMs) or loop over a batch of it (VCT injection, the volumetric march); shadow
// map textures stay bound by each pass.
#pragma once

#include "common/light.h"
#include "gi/gl/handle.h"
#include "gi/render/pass.h"
#include "gi/scene/scene.h"
#include "gi/scene/scene_settings.h"

#include <glm/glm.hpp>

#include <vector>

namespace gi {

// Light l as the GPU reads it; the shadow fields are left for setShadowProjection. An area light
// takes its shape from `emitter` (its triangles start at `firstTriangle` of the area buffer);
// without one it packs as a lobe with no area (its light is nothing).
light::GPULight packLight(const LightSettings& l, const Emitter* emitter = nullptr, int firstTriangle = 0);

// The factor on an emitter's emission that light l gives: colour x intensity.
glm::vec3 emissionScale(const LightSettings& l);

// Fills g's shadow fields: the projection of light l's shadow map (square, `size` texels) over a
// scene with bounds b. Directional: an orthographic box around the scene's bounding sphere;
// spot: a perspective frustum (spotViewProj); point: a cube reaching `far`.
void setShadowProjection(light::GPULight& g, const LightSettings& l, const Bounds& b, int size);

// World to clip space of a spot light's square perspective map (shadow map or RSM) at
// `position` looking along unit `dir`, with field of view fovDeg, reaching `far`.
glm::mat4 spotViewProj(const glm::vec3& position, const glm::vec3& dir, float fovDeg, float far);

// A point light's cube faces, in GL's order (+X, -X, +Y, -Y, +Z, -Z).
inline constexpr int kCubeFaceCount = 6;
// World to clip space of face `face` of a cube map (shadow map or RSM) centred on `position`,
// 90 degrees wide, reaching `far`, oriented as GL samples cube maps.
glm::mat4 cubeFaceViewProj(const glm::vec3& position, int face, float far);

// Binds entry i of a pass's light batch's shadow map, when it has one, to unit2D + i or
// unitCube + i as its type needs; samplers are the caller's.
void bindBatchShadowMap(int i, const ShadowMapView& sm, GLuint unit2D, GLuint unitCube);

class LightBuffer {
public:
    // Packs the lights with their shadow projections, uploads them and binds the buffer at
    // light::kLightBufferBinding for every pass of the frame; the area lights' triangles at
    // light::kAreaTriangleBinding and each emitter's factor at light::kEmitterScaleBinding.
    void upload(const std::vector<LightSettings>& lights, const std::vector<Emitter>& emitters, const Bounds& sceneBounds,
                int shadowSize);
    const light::GPULight& operator[](size_t i) const { return mLights[i]; }
    // Light i with its triangles when it is an area light of at most kAreaMaxExactTriangles.
    light::GPULightWithTriangles withTriangles(size_t i) const;

private:
    std::vector<light::GPULight> mLights;
    std::vector<light::GPUAreaTriangle> mTriangles;
    std::vector<glm::vec4> mScales;
    gl::Buffer mBuffer, mTriangleBuffer, mScaleBuffer;
    size_t mCapacity = 0, mTriangleCapacity = 0, mScaleCapacity = 0;  // entries each buffer holds
};

}  // namespace gi
