// Camera matrices from CameraSettings, shared by the raster pipeline and the path tracer so
// both see exactly the same view.
#pragma once

#include "gi/scene/scene_settings.h"

#include <glm/glm.hpp>

namespace gi {

glm::mat4 viewMatrix(const CameraSettings& c);
glm::mat4 projectionMatrix(const CameraSettings& c, float aspect);

// Takes the view of one of the scene's cameras (a glTF camera, or the one framing the scene):
// eye, target, up, field of view and clip planes. A scene in millimetres lies past the default
// far plane, so the clip planes travel with the view.
void takeSceneCamera(CameraSettings& camera, const CameraSettings& sceneCamera);

// The camera the raster pipeline draws with: its near plane moved up to half the distance at
// which the scene's bounding sphere (centre, radius) begins in front of the eye, never back, and
// never past half the far plane, so nothing of the scene is clipped. A conventional depth buffer's
// precision is set by near / distance: a file's camera with near 0.05 looking at a model in
// millimetres from 1.6 m away (2CylinderEngine) put its surfaces 4 shadow-map texels apart from
// where they were drawn, and the sun's shadow speckled them. The path-traced reference keeps the
// camera as given (its rays need no depth buffer).
CameraSettings rasterCamera(const CameraSettings& c, const glm::vec3& center, float radius);

}  // namespace gi
