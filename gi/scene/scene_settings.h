// Camera and light settings: what a preset stores about the view and the lights.
#pragma once

#include "gi/preset/settings.h"

#include <glm/vec3.hpp>

namespace gi {

struct CameraSettings {
    static constexpr std::string_view kSection = "camera";
    glm::vec3 eye{0.0f, 1.0f, 3.4f};     // world position of the eye
    glm::vec3 target{0.0f, 1.0f, 0.0f};  // world point the camera looks at
    glm::vec3 up{0.0f, 1.0f, 0.0f};      // world up; need not be orthogonal to the view
    float fovY = 40.0f;                  // vertical field of view, degrees, 1..170
    float near = 0.05f;                  // near plane distance, world units
    float far = 100.0f;                  // far plane distance, world units
    int sceneCamera = -1;                // index of a camera from the glTF file; -1 uses eye/target

    template <class V>
    void visit(V&& v) {
        v(eye, {"eye", "Eye position in world space", "m", -1e6, 1e6});
        v(target, {"target", "Point the camera looks at", "m", -1e6, 1e6});
        v(up, forDevelopers({"up", "World up direction", "", -1, 1}));
        v(fovY, {"fovY", "Vertical field of view", "deg", 1, 170});
        v(near, forDevelopers({"near", "Near clip plane distance", "m", 1e-4, 1e4}));
        v(far, forDevelopers({"far", "Far clip plane distance", "m", 1e-3, 1e7}));
        v(sceneCamera, forDevelopers({"sceneCamera", "Use the glTF file's camera with this index (-1: eye/target)", "", -1, 1023}));
    }
};

// A named view saved in the preset (the editor's Camera section: add, name, jump).
struct CameraBookmark {
    static constexpr std::string_view kSection = "bookmarks";
    std::string name = "view";          // what the list shows
    glm::vec3 eye{0.0f, 1.0f, 3.4f};    // world position of the eye
    glm::vec3 target{0.0f, 1.0f, 0.0f}; // world point the camera looks at
    float fovY = 40.0f;                 // vertical field of view, degrees, 1..170

    template <class V>
    void visit(V&& v) {
        v(name, {"name", "Name of the view", "", 0, 0});
        v(eye, {"eye", "Eye position in world space", "m", -1e6, 1e6});
        v(target, {"target", "Point the camera looks at", "m", -1e6, 1e6});
        v(fovY, {"fovY", "Vertical field of view", "deg", 1, 170});
    }
};

// Area lights are the scene's emissive surfaces (gi/scene/scene.h Emitter), one light per
// emitter: the scene lists them beside its punctual lights, and a preset names them by index to
// switch them off, tint or scale them. Their shape, position and direction come from the scene.
enum class LightType { Directional, Point, Spot, Area };
template <>
struct EnumNames<LightType> {
    static constexpr std::array<std::pair<LightType, const char*>, 4> values{{{LightType::Directional, "directional"},
                                                                             {LightType::Point, "point"},
                                                                             {LightType::Spot, "spot"},
                                                                             {LightType::Area, "area"}}};
};

struct LightSettings {
    static constexpr std::string_view kSection = "lights";
    LightType type = LightType::Directional;        // directional, point or spot
    glm::vec3 color{1.0f, 1.0f, 1.0f};              // linear RGB tint
    bool enabled = true;                            // a light switched off is left out of the frame
    float intensity = 3.0f;                         // illuminance (directional), intensity (point/spot), scale (area)
    glm::vec3 position{0.0f, 5.0f, 0.0f};           // point and spot: world position
    glm::vec3 direction{-0.35f, -0.88f, 0.32f};     // directional and spot: direction the light travels
    float range = 0.0f;                             // point and spot: glTF range window, 0 = infinite
    float innerConeDeg = 20.0f;                     // spot: full intensity inside this half-angle
    float outerConeDeg = 30.0f;                     // spot: zero intensity outside this half-angle
    bool castShadows = true;                        // render a shadow map for this light
    int emitter = -1;                               // area: index of the scene's emitter

    template <class V>
    void visit(V&& v) {
        v(type, {"type", "Light type", "", 0, 0, Cost::Reallocate});
        v(enabled, {"enabled", "Light the scene with it", "", 0, 0, Cost::Reallocate});
        v(color, {"color", "Linear RGB colour (area: a tint of the surface's emission)", "", 0, 1e3});
        v(intensity, {"intensity", "Illuminance (directional), radiant intensity (point, spot) or emission scale (area)", "", 0, 1e7});
        v(position, {"position", "World position (point, spot)", "m", -1e6, 1e6});
        v(direction, {"direction", "Direction the light travels (directional, spot)", "", -1e3, 1e3});
        v(range, {"range", "Distance where the light fades to zero (0: infinite)", "m", 0, 1e6});
        v(innerConeDeg, {"innerConeDeg", "Spot half-angle of full intensity", "deg", 0, 89.9});
        v(outerConeDeg, {"outerConeDeg", "Spot half-angle where intensity reaches zero", "deg", 0.1, 90});
        v(castShadows, {"castShadows", "Render a shadow map for this light", "", 0, 0, Cost::Reallocate});
        v(emitter, forDevelopers({"emitter", "Area: the scene's emissive surface (its index in the Lights panel)", "", -1, 1023, Cost::Reallocate}));
    }

    // An area light's position and direction are its emitter's centroid and normal, placed
    // every frame (placeAreaLight): shown, not edited.
    const char* readOnly(std::string_view key) const {
        if (type == LightType::Area && (key == "position" || key == "direction"))
            return "an area light's position and direction are its emissive surface's centroid and normal";
        return nullptr;
    }
};

}  // namespace gi
