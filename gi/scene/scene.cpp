#include "gi/scene/scene.h"

#include "gi/scene/emitters.h"
#include "gi/scene/mesh_builder.h"

#include "gi/util/error.h"
#include "gi/util/paths.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace gi {

void Scene::finalize() {
    std::stable_sort(draws.begin(), draws.end(), [](const Draw& a, const Draw& b) { return a.material < b.material; });
    // Reorder indices so each material's triangles are contiguous, then merge draws.
    std::vector<uint32_t> sorted;
    sorted.reserve(indices.size());
    std::vector<Draw> merged;
    for (const Draw& d : draws) {
        uint32_t first = uint32_t(sorted.size());
        sorted.insert(sorted.end(), indices.begin() + d.firstIndex, indices.begin() + d.firstIndex + d.indexCount);
        if (!merged.empty() && merged.back().material == d.material) merged.back().indexCount += d.indexCount;
        else merged.push_back({first, d.indexCount, d.material});
    }
    indices = std::move(sorted);
    draws = std::move(merged);
    bounds = Bounds();
    for (uint32_t i : indices) bounds.grow(vertices[i].position);
    buildEmitters(*this);
}

namespace {

// A small plank texture for the crate, so the built-in scene exercises the texture path.
Texture crateTexture() {
    Texture t;
    t.name = "crate";
    t.width = t.height = 64;
    t.rgba.resize(64 * 64 * 4);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            bool border = x < 5 || x >= 59 || y < 5 || y >= 59;
            bool seam = (y % 18) == 0;
            bool brace = std::abs(x - y) < 4 || std::abs(x - (63 - y)) < 4;
            float grain = 0.9f + 0.1f * std::sin(float(y) * 1.7f + std::sin(float(x) * 0.3f) * 2.0f);
            float shade = (border || brace) ? 0.75f : (seam ? 0.45f : 1.0f);
            uint8_t* p = &t.rgba[(y * 64 + x) * 4];
            p[0] = uint8_t(std::clamp(200.0f * shade * grain, 0.0f, 255.0f));
            p[1] = uint8_t(std::clamp(150.0f * shade * grain, 0.0f, 255.0f));
            p[2] = uint8_t(std::clamp(95.0f * shade * grain, 0.0f, 255.0f));
            p[3] = 255;
        }
    return t;
}

// The built-in Cornell box's room and boxes, without lights or camera: x and z span -1..1,
// y 0..2 (the scale of the McGuire CornellBox-Original set).
void cornellRoom(Scene& s) {
    MeshBuilder b(s);
    // Colours are the Kd values of the McGuire CornellBox-Original set.
    int white = b.material("white", {0.725f, 0.71f, 0.68f});
    int red = b.material("red", {0.63f, 0.065f, 0.05f});
    int green = b.material("green", {0.14f, 0.45f, 0.091f});
    b.quad(white, {-1, 0, 1}, {2, 0, 0}, {0, 0, -2});    // floor, +y
    b.quad(white, {-1, 2, -1}, {2, 0, 0}, {0, 0, 2});    // ceiling, -y
    b.quad(white, {-1, 0, -1}, {2, 0, 0}, {0, 2, 0});    // back wall, +z
    b.quad(red, {-1, 0, 1}, {0, 0, -2}, {0, 2, 0});      // left wall, +x
    b.quad(green, {1, 0, -1}, {0, 0, 2}, {0, 2, 0});     // right wall, -x
    b.box(white, {0.33f, 0.3f, 0.30f}, {0.3f, 0.3f, 0.3f}, -17.0f);   // short box
    b.box(white, {-0.34f, 0.6f, -0.30f}, {0.3f, 0.6f, 0.3f}, 20.0f);  // tall box
}

Scene makeCornell() {
    Scene s;
    s.name = "cornell";
    cornellRoom(s);
    // A wide downward spot just below the ceiling stands in for the ceiling lamp.
    LightSettings lamp;
    lamp.type = LightType::Spot;
    lamp.position = {0.0f, 1.95f, 0.0f};
    lamp.direction = {0.0f, -1.0f, 0.0f};
    lamp.intensity = 6.0f;
    lamp.color = {1.0f, 0.85f, 0.65f};
    lamp.innerConeDeg = 40.0f;
    lamp.outerConeDeg = 80.0f;
    s.lights.push_back(lamp);
    CameraSettings cam;  // the defaults are the classic Cornell view
    s.cameras.push_back(cam);
    s.finalize();
    return s;
}

// The same room lit only by an emissive quad 2 cm under the ceiling, as in CornellBox-Original:
// its light's size, place and emission (Ke 17, 12, 4: emissiveFactor (1, 0.706, 0.235) x
// strength 17), so the area-light path is scored without ../shared. No punctual light: the
// quad is the frame's one light, an area light, and no default sun is added.
Scene makeCornellLamp() {
    Scene s;
    s.name = "cornell_lamp";
    cornellRoom(s);
    MeshBuilder b(s);
    int lamp = b.material("lamp", {0.78f, 0.78f, 0.78f}, 0.41f);
    s.materials[size_t(lamp)].emissive = glm::vec3(1.0f, 0.70588f, 0.23529f) * 17.0f;
    b.quad(lamp, {-0.24f, 1.98f, -0.22f}, {0.47f, 0, 0}, {0, 0, 0.38f});  // faces -y
    CameraSettings cam;
    s.cameras.push_back(cam);
    s.finalize();
    return s;
}

Scene makeBasic() {
    Scene s;
    s.name = "basic";
    MeshBuilder b(s);
    s.textures.push_back(crateTexture());
    int floor = b.material("floor", {0.8f, 0.7f, 0.4f}, 0.9f);
    int crate = b.material("crate", {1.0f, 1.0f, 1.0f}, 0.7f, 0);
    int red = b.material("redSphere", {0.8f, 0.05f, 0.05f}, 0.4f);
    b.quad(floor, {-6, 0, 6}, {12, 0, 0}, {0, 0, -12}, {6, 6});
    b.box(crate, {0.0f, 0.5f, 0.0f}, {0.5f, 0.5f, 0.5f}, 25.0f);
    b.sphere(red, {1.25f, 0.45f, 0.55f}, 0.45f);
    LightSettings sun;
    sun.type = LightType::Directional;
    sun.direction = {-0.4f, -0.8f, -0.45f};
    sun.intensity = 3.0f;
    s.lights.push_back(sun);
    CameraSettings cam;
    cam.eye = {3.2f, 2.2f, 3.6f};
    cam.target = {0.5f, 0.35f, 0.2f};
    cam.fovY = 45.0f;
    s.cameras.push_back(cam);
    s.finalize();
    return s;
}

// Seed 004's glossy spheres for environment lighting: two rows of five spheres, gold metal above
// and a white dielectric below, roughness 0.05, 0.25, 0.5, 0.75, 1 from left to right, floating
// (no floor: the environment lights them from every side). No lights of its own.
Scene makeSpheres() {
    Scene s;
    s.name = "spheres";
    MeshBuilder b(s);
    const float roughness[5] = {0.05f, 0.25f, 0.5f, 0.75f, 1.0f};
    for (int i = 0; i < 5; ++i) {
        float x = (float(i) - 2.0f) * 1.1f;
        int metal = b.material("gold" + std::to_string(i), {1.0f, 0.78f, 0.34f}, roughness[i]);
        s.materials[size_t(metal)].metallic = 1.0f;
        int plastic = b.material("white" + std::to_string(i), {0.8f, 0.8f, 0.8f}, roughness[i]);
        b.sphere(metal, {x, 0.6f, 0.0f}, 0.5f);
        b.sphere(plastic, {x, -0.6f, 0.0f}, 0.5f);
    }
    CameraSettings cam;
    cam.eye = {0.0f, 0.0f, 6.5f};
    cam.target = {0.0f, 0.0f, 0.0f};
    cam.fovY = 45.0f;
    s.cameras.push_back(cam);
    s.finalize();
    return s;
}

// The leak scene: two rooms 2 x 2 x 2 m side by side, sharing one thin wall (a single quad) at
// x = 0. A spot light lights room A (x < 0); room B (x > 0) is closed, so in the reference it is
// dark and whatever indirect light a technique puts there has leaked through the wall. Camera 0
// looks at the shared wall from room A, camera 1 into room B from its outer wall.
Scene makeTwoRooms() {
    Scene s;
    s.name = "two_rooms";
    MeshBuilder b(s);
    int white = b.material("white", glm::vec3(0.8f), 1.0f);
    b.quad(white, {-2, 0, 1}, {4, 0, 0}, {0, 0, -2});    // floor
    b.quad(white, {-2, 2, -1}, {4, 0, 0}, {0, 0, 2});    // ceiling
    b.quad(white, {-2, 0, -1}, {4, 0, 0}, {0, 2, 0});    // back
    b.quad(white, {2, 0, 1}, {-4, 0, 0}, {0, 2, 0});     // front
    b.quad(white, {-2, 0, 1}, {0, 0, -2}, {0, 2, 0});    // outer wall of A
    b.quad(white, {2, 0, -1}, {0, 0, 2}, {0, 2, 0});     // outer wall of B
    b.quad(white, {0, 0, -1}, {0, 0, 2}, {0, 2, 0});     // the shared thin wall
    LightSettings spot;
    spot.type = LightType::Spot;
    spot.position = {-1.8f, 1.8f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(1.0f, -0.6f, 0.0f));
    spot.intensity = 20.0f;
    spot.innerConeDeg = 50.0f;
    spot.outerConeDeg = 70.0f;
    s.lights.push_back(spot);
    CameraSettings lit, closed;
    lit.eye = {-1.9f, 1.0f, 0.0f};
    lit.target = {0.0f, 0.8f, 0.0f};
    lit.fovY = 70.0f;
    closed = lit;
    closed.eye = {1.9f, 1.0f, 0.0f};
    s.cameras = {lit, closed};
    s.cameraNames = {"the lit room, facing the shared wall", "the closed room, facing the shared wall"};
    s.finalize();
    return s;
}

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"cornell", "cornell_lamp", "basic", "spheres", "two_rooms"}; }

bool isBuiltinScene(const std::string& name) {
    for (auto& n : builtinSceneNames())
        if (n == name) return true;
    return false;
}

Scene makeBuiltinScene(const std::string& name) {
    if (name == "cornell") return makeCornell();
    if (name == "cornell_lamp") return makeCornellLamp();
    if (name == "basic") return makeBasic();
    if (name == "spheres") return makeSpheres();
    if (name == "two_rooms") return makeTwoRooms();
    std::string valid;
    for (const std::string& n : builtinSceneNames()) valid += (valid.empty() ? "" : ", ") + n;
    throw Error("unknown built-in scene '" + name + "' (valid: " + valid + ")");
}

Scene loadScene(const std::string& scene, const std::filesystem::path& presetFolder, double memoryBudgetMB) {
    if (isBuiltinScene(scene)) return makeBuiltinScene(scene);
    if (scene.empty()) throw Error("key 'scene': empty (a built-in scene name or a glTF file path)");
    Scene s = loadGLTF(resolveAsset(scene, presetFolder), memoryBudgetMB);
    if (s.cameras.empty()) {
        s.cameras.push_back(frameBounds(s.bounds));
        s.cameraNames = {"framing the scene (the file has no camera)"};
        s.framedCamera = true;  // frameCameraless (gi/reference/framing.h) may look from inside
    }
    return s;
}

CameraSettings frameBounds(const Bounds& b) {
    CameraSettings c;
    const float radius = b.radius();
    c.target = b.center();
    c.fovY = 40.0f;
    float dist = radius / std::sin(glm::radians(c.fovY * 0.5f));
    c.eye = c.target + glm::normalize(glm::vec3(0.6f, 0.45f, 1.0f)) * dist;
    // Near is fitted to the scene's size, not to the distance: walking into the scene (a closed
    // room framed from outside) must not clip its walls.
    c.near = radius * 2e-3f;
    c.far = (dist + radius) * 1.5f;
    return c;
}

}  // namespace gi
