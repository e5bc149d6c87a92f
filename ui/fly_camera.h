// Fly camera for the viewport: hold the right mouse button and move the mouse to look, WASD to
// move, Q/E down/up, Shift to go faster. It edits CameraSettings eye/target in place, so the
// Camera panel and saved presets always show the view on screen.
#pragma once

#include "gi/scene/scene_settings.h"

namespace gi::ui {

class FlyCamera {
public:
    // Applies this frame's mouse and keyboard input unless ImGui wants them. `sceneRadius` scales
    // the speed so small and large scenes both cross in a few seconds. Returns true on a change.
    bool update(CameraSettings& camera, float dt, float sceneRadius) const;

private:
    static constexpr float kLookRadiansPerPixel = 0.004f;
    static constexpr float kRadiiPerSecond = 0.6f;
    static constexpr float kFastFactor = 4.0f;
};

}  // namespace gi::ui
