// Camera matrices from CameraSettings, shared by the raster pipeline and the path tracer so
// both see exactly the same view.
#pragma once

#include "gi/scene/scene_settings.h"

#include <glm/glm.hpp>

namespace gi {

glm::mat4 viewMatrix(const CameraSettings& c);
glm::mat4 projectionMatrix(const CameraSettings& c, float aspect);

}  // namespace gi
