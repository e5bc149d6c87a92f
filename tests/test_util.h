// Helpers shared by the tests: a process-wide EGL context, temporary folders, running commands.
#pragma once

#include "gi/platform/egl_context.h"
#include "gi/render/renderer.h"
#include "gi/scene/scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

namespace gi::test {

// The one headless context of the test process, created on first use.
EGLContextHeadless& context();

// A fresh empty folder under the system temp dir, named after the running test.
std::filesystem::path tempDir();

struct CommandResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};
CommandResult runCommand(const std::string& command);

// The built-in two_rooms scene (gi/scene/scene.cpp): two rooms sharing one thin wall at x = 0,
// a spot light in room A (x < 0), room B (x > 0) closed and so dark in the reference.
Scene twoRooms();
// Its closed room B seen from its outer wall (the scene's camera 1: eye, target, 70 degree
// field of view): the view the leak tests average the indirect light of.
void lookIntoClosedRoom(CameraSettings& camera);
// The alignment leak tests: the two-room scene with two tiny black quads `margin` outside its
// bounds after its own vertices, which hold a grid fitted to the bounds while the rooms move.
struct AnchoredRooms {
    Scene scene;
    size_t roomVertices = 0;  // the rooms' vertices, before the anchors'
    // The rooms and their light moved by offset; the anchors stay.
    Scene moved(glm::vec3 offset) const;
};
AnchoredRooms anchoredTwoRooms(float margin);
// The mean indirect light of the closed room seen from its outer wall (lookIntoClosedRoom) and of
// the lit room looking away from the shared wall, both views moved by offset with the rooms.
struct RoomsIndirect {
    double closed = 0.0, lit = 0.0;
};
RoomsIndirect twoRoomsIndirect(Renderer& r, FrameSettings fs, glm::vec3 offset);
// The sky tests: a 4 x 4 m floor of albedo 0.8 on its own, the same floor inside a closed box
// 1 m high, and a frame of `technique` looking straight down at the floor's centre from 0.6 m,
// lit only by a constant environment of radiance 1 (no light).
Scene openFloor();
// A closed room 4 x 3 x 4 m (x and z from -2 to 2, y from 0 to 3) with no light: floor,
// ceiling, back and front of albedo `white` (material 0), the wall at -x of `left` (material 1)
// and the one at +x of `right` (material 2).
Scene closedRoom(float white = 0.8f, glm::vec3 left = glm::vec3(0.8f), glm::vec3 right = glm::vec3(0.8f));
// A point light (the light's other settings at their defaults).
LightSettings pointLight(glm::vec3 position, float intensity);
Scene closedBox();
// A scene of one box of half size `half`, turned yawDeg about +y, its faces of the given albedo.
Scene box(glm::vec3 centre, glm::vec3 half, float yawDeg, float albedo);
// The scale tests: a built-in scene with every vertex scaled about the origin, and a camera
// (eye, target and clip planes) scaled with it, so the view is the same at any size.
Scene scaledBuiltinScene(const std::string& name, float scale);
void scaleCamera(CameraSettings& camera, float scale);
FrameSettings skyFrame(const Scene& scene, const std::string& technique);
// Mean luminance of the indirect light the lighting pass adds (Renderer::readIndirectRadiance)
// after rendering fs. With GI_TEST_IMAGES=DIR set, it also writes the image it averaged as
// DIR/SUITE_TEST_K.exr, K counting the test's measurements from 0 (to see what a figure means:
// where a leak is, what a sky test's floor gathered).
double meanIndirect(Renderer& r, const FrameSettings& fs);
// A fresh renderer that has drawn fs keeping nothing from earlier frames (render.keepStaticWork
// off): what a renderer that kept its static work must match, pixel for pixel.
std::unique_ptr<Renderer> renderedAfresh(const Scene& scene, FrameSettings fs);
// Mean luminance of the path tracer's one bounce of indirect light for fs (two surface bounces,
// indirect paths only, 256 spp; cached), the light a single-bounce technique gathers.
// `cached` says whether it came from the cache.
double referenceOneBounceIndirect(const Scene& scene, const FrameSettings& fs, bool* cached = nullptr);

// A GL test fails on any GL debug error raised during it.
class GLTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;

private:
    uint64_t mErrorsBefore = 0;
};

}  // namespace gi::test
