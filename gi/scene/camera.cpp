#include "gi/scene/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace gi {

glm::mat4 viewMatrix(const CameraSettings& c) {
    glm::vec3 f = c.target - c.eye;
    if (glm::length(f) < 1e-8f) f = glm::vec3(0, 0, -1);
    glm::vec3 up = c.up;
    if (glm::length(glm::cross(glm::normalize(f), up)) < 1e-4f) up = std::abs(f.y) > 0.9f * glm::length(f) ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    return glm::lookAt(c.eye, c.eye + f, up);
}

glm::mat4 projectionMatrix(const CameraSettings& c, float aspect) {
    float far = std::max(c.far, c.near * 1.001f);
    return glm::perspective(glm::radians(c.fovY), aspect, c.near, far);
}

void takeSceneCamera(CameraSettings& camera, const CameraSettings& sceneCamera) {
    camera.eye = sceneCamera.eye;
    camera.target = sceneCamera.target;
    camera.up = sceneCamera.up;
    camera.fovY = sceneCamera.fovY;
    camera.near = sceneCamera.near;
    camera.far = sceneCamera.far;
}

CameraSettings rasterCamera(const CameraSettings& c, const glm::vec3& center, float radius) {
    CameraSettings out = c;
    glm::vec3 f = c.target - c.eye;
    if (glm::length(f) < 1e-8f) return out;
    float nearest = glm::dot(center - c.eye, glm::normalize(f)) - radius;
    float fitted = std::min(0.5f * nearest, 0.5f * c.far);
    if (std::isfinite(fitted) && fitted > c.near) out.near = fitted;
    return out;
}

}  // namespace gi
