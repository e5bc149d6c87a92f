#include "ui/fly_camera.h"

#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace gi::ui {

bool FlyCamera::update(CameraSettings& camera, float dt, float sceneRadius) const {
    const ImGuiIO& io = ImGui::GetIO();
    glm::vec3 offset = camera.target - camera.eye;
    float distance = glm::length(offset);
    if (distance <= 0.0f) return false;
    glm::vec3 up = glm::length(camera.up) > 0.0f ? glm::normalize(camera.up) : glm::vec3(0, 1, 0);
    glm::vec3 forward = offset / distance;
    bool changed = false;

    // Not on the press itself: the pointer may have jumped there since the last frame.
    bool looking = ImGui::IsMouseDown(ImGuiMouseButton_Right) && !ImGui::IsMouseClicked(ImGuiMouseButton_Right);
    if (!io.WantCaptureMouse && looking && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
        glm::vec3 right = glm::normalize(glm::cross(forward, up));
        glm::quat yaw = glm::angleAxis(-io.MouseDelta.x * kLookRadiansPerPixel, up);
        glm::quat pitch = glm::angleAxis(-io.MouseDelta.y * kLookRadiansPerPixel, right);
        glm::vec3 turned = glm::normalize(yaw * (pitch * forward));
        // Stop short of the poles, where the right vector (and so the view) would flip.
        if (std::abs(glm::dot(turned, up)) > 0.99f) turned = glm::normalize(yaw * forward);
        forward = turned;
        camera.target = camera.eye + forward * distance;
        changed = true;
    }

    if (!io.WantCaptureKeyboard) {
        glm::vec3 right = glm::normalize(glm::cross(forward, up));
        glm::vec3 move{0.0f};
        auto key = [](int k) { return ImGui::IsKeyDown(k) ? 1.0f : 0.0f; };
        move += forward * (key(GLFW_KEY_W) - key(GLFW_KEY_S));
        move += right * (key(GLFW_KEY_D) - key(GLFW_KEY_A));
        move += up * (key(GLFW_KEY_E) - key(GLFW_KEY_Q));
        if (glm::length(move) > 0.0f) {
            float speed = kRadiiPerSecond * std::max(sceneRadius, 1e-3f) * (io.KeyShift ? kFastFactor : 1.0f);
            move = glm::normalize(move) * speed * dt;
            camera.eye += move;
            camera.target += move;
            changed = true;
        }
    }
    return changed;
}

}  // namespace gi::ui
