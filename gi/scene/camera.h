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

}  // namespace gi
