// Where a file with no camera is viewed from (gi/reference/framing.h), on rooms and objects
// made of quads whose normals face where they are meant to be seen from; and the near plane the
// raster draws a view with (gi/scene/camera.h rasterCamera).
#include "gi/reference/framing.h"
#include "gi/scene/camera.h"
#include "gi/scene/mesh_builder.h"

#include <gtest/gtest.h>

#include <limits>

namespace gi {
namespace {

bool insideBounds(const Bounds& b, glm::vec3 p) {
    return glm::all(glm::greaterThan(p, b.min)) && glm::all(glm::lessThan(p, b.max));
}

// A room 8 x 3 x 4 m (x, y, z) from the origin, its walls facing in, with a pillar; `openFront`
// leaves out the +z wall.
Scene room(bool openFront) {
    Scene s;
    s.name = "room";
    MeshBuilder b(s);
    int m = b.material("white", glm::vec3(0.8f));
    const glm::vec3 lo(0.0f), hi(8.0f, 3.0f, 4.0f);
    b.quad(m, {lo.x, lo.y, lo.z}, {0, 0, hi.z}, {hi.x, 0, 0});             // floor, up
    b.quad(m, {lo.x, hi.y, lo.z}, {hi.x, 0, 0}, {0, 0, hi.z});             // ceiling, down
    b.quad(m, {lo.x, lo.y, lo.z}, {hi.x, 0, 0}, {0, hi.y, 0});             // back (z = 0), +z
    if (!openFront) b.quad(m, {lo.x, lo.y, hi.z}, {0, hi.y, 0}, {hi.x, 0, 0});  // front, -z
    b.quad(m, {lo.x, lo.y, lo.z}, {0, hi.y, 0}, {0, 0, hi.z});             // x = 0, +x
    b.quad(m, {hi.x, lo.y, lo.z}, {0, 0, hi.z}, {0, hi.y, 0});             // x = 8, -x
    b.box(m, {2.0f, 0.75f, 1.0f}, glm::vec3(0.3f, 0.75f, 0.3f), 0.0f);    // a pillar, facing out
    s.finalize();
    return s;
}

TEST(Framing, AClosedRoomIsViewedFromInsideAlongItsLongAxis) {
    Scene s = room(false);
    Framing f = frameScene(s, PathTracer(s));
    EXPECT_TRUE(f.inside) << f.how;
    EXPECT_TRUE(insideBounds(s.bounds, f.camera.eye)) << f.how;
    glm::vec3 d = glm::normalize(f.camera.target - f.camera.eye);
    EXPECT_GT(std::abs(d.x), 0.99f) << "the room is longest along x: " << f.how;
    // 90 % of the way to the end wall at most: the wall is in front of the near plane.
    EXPECT_GT(std::min(f.camera.eye.x, 8.0f - f.camera.eye.x), 0.3f) << f.how;
    EXPECT_LT(f.camera.near, 0.05f);
}

TEST(Framing, ABoxOpenOnOneSideIsViewedThroughIt) {
    Scene s = room(true);
    Framing f = frameScene(s, PathTracer(s));
    EXPECT_TRUE(f.inside) << f.how;
    EXPECT_GT(f.camera.eye.z, 4.0f) << "outside the open front: " << f.how;
    glm::vec3 d = glm::normalize(f.camera.target - f.camera.eye);
    EXPECT_LT(d.z, -0.99f) << f.how;
    EXPECT_NEAR(f.camera.eye.y, 1.5f, 1e-4f);
}

TEST(Framing, AnObjectKeepsTheOutsideView) {
    Scene s;
    MeshBuilder b(s);
    b.box(b.material("grey", glm::vec3(0.5f)), glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 0.5f), 20.0f);
    s.finalize();
    Framing f = frameScene(s, PathTracer(s));
    EXPECT_FALSE(f.inside) << f.how;
    CameraSettings outside = frameBounds(s.bounds);
    EXPECT_EQ(f.camera.eye, outside.eye);
    EXPECT_FALSE(insideBounds(s.bounds, f.camera.eye));
}

TEST(Framing, OnlyACameraLoadSceneMadeIsReplaced) {
    Scene s = room(false);
    CameraSettings own;
    own.eye = {100.0f, 0.0f, 0.0f};
    s.cameras = {own};
    EXPECT_EQ(frameCameraless(s), "");
    EXPECT_EQ(s.cameras[0].eye, own.eye);
    s.framedCamera = true;
    EXPECT_NE(frameCameraless(s), "");
    EXPECT_TRUE(insideBounds(s.bounds, s.cameras[0].eye));
}

// The raster's near plane (rasterCamera): moved up towards the scene's bounding sphere when the
// eye is far outside it, never back, never past half the far plane, and never in front of any
// point of the sphere, so nothing is clipped.
TEST(RasterCamera, TheNearPlaneMovesUpToTheSceneAndNeverClipsIt) {
    CameraSettings c;
    c.eye = {1000.0f, 800.0f, 950.0f};
    c.target = {0.0f, 0.0f, 0.0f};
    c.near = 0.05f;
    c.far = 1e6f;
    const glm::vec3 centre(10.0f, -5.0f, 0.0f);
    const float radius = 400.0f;
    CameraSettings r = rasterCamera(c, centre, radius);
    EXPECT_GT(r.near, 100.0f);
    const glm::vec3 forward = glm::normalize(c.target - c.eye);
    const float nearestPoint = glm::dot(centre - c.eye, forward) - radius;
    EXPECT_LT(r.near, nearestPoint);
    EXPECT_EQ(r.far, c.far);
    EXPECT_EQ(r.eye, c.eye);
    EXPECT_EQ(r.fovY, c.fovY);
    // An eye inside the sphere (a room walked into) keeps its near plane.
    c.eye = centre + glm::vec3(100.0f, 0.0f, 0.0f);
    EXPECT_EQ(rasterCamera(c, centre, radius).near, c.near);
    // Never past half the far plane; never back from the near plane the camera had.
    c.eye = {0.0f, 0.0f, 5000.0f};
    c.far = 2000.0f;
    EXPECT_FLOAT_EQ(rasterCamera(c, centre, radius).near, 1000.0f);
    c.near = 3000.0f;
    c.far = 1e6f;
    EXPECT_EQ(rasterCamera(c, centre, radius).near, 3000.0f);
    // An empty scene's bounds (an infinite radius) change nothing.
    c.near = 0.05f;
    EXPECT_EQ(rasterCamera(c, glm::vec3(0.0f), std::numeric_limits<float>::infinity()).near, c.near);
}

}  // namespace
}  // namespace gi
