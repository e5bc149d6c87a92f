#include "test_util.h"

#include "gi/gl/debug.h"
#include "gi/metrics/metrics.h"
#include "gi/preset/preset.h"
#include "gi/reference/reference_cache.h"
#include "gi/render/image_io.h"
#include "gi/scene/mesh_builder.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace gi::test {

EGLContextHeadless& context() {
    static EGLContextHeadless ctx;
    return ctx;
}

namespace {

// SUITE_NAME of the running test, with anything but letters and digits made '_' (a file name).
std::string currentTestName() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (auto& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

}  // namespace

std::filesystem::path tempDir() {
    auto dir = std::filesystem::temp_directory_path() / "gi_tests" / currentTestName();
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

Scene twoRooms() { return makeBuiltinScene("two_rooms"); }

void lookIntoClosedRoom(CameraSettings& camera) {
    const CameraSettings& closed = makeBuiltinScene("two_rooms").cameras[1];
    camera.eye = closed.eye;
    camera.target = closed.target;
    camera.fovY = closed.fovY;
}

AnchoredRooms anchoredTwoRooms(float margin) {
    AnchoredRooms a;
    a.scene = twoRooms();
    a.roomVertices = a.scene.vertices.size();
    const Bounds bounds = a.scene.bounds;
    MeshBuilder b(a.scene);
    int anchor = b.material("anchor", glm::vec3(0.0f), 1.0f);
    b.quad(anchor, bounds.min - glm::vec3(margin), {1e-3f, 0, 0}, {0, 1e-3f, 0});
    b.quad(anchor, bounds.max + glm::vec3(margin), {-1e-3f, 0, 0}, {0, -1e-3f, 0});
    a.scene.finalize();
    return a;
}

Scene AnchoredRooms::moved(glm::vec3 offset) const {
    Scene s = scene;
    for (size_t i = 0; i < roomVertices; ++i) s.vertices[i].position += offset;
    for (LightSettings& l : s.lights) l.position += offset;
    s.finalize();
    return s;
}

RoomsIndirect twoRoomsIndirect(Renderer& r, FrameSettings fs, glm::vec3 offset) {
    RoomsIndirect result;
    lookIntoClosedRoom(fs.camera);
    fs.camera.eye += offset;
    fs.camera.target += offset;
    result.closed = meanIndirect(r, fs);
    fs.camera.eye = glm::vec3(-0.1f, 1.0f, 0.0f) + offset;
    fs.camera.target = glm::vec3(-2.0f, 0.8f, 0.0f) + offset;
    result.lit = meanIndirect(r, fs);
    return result;
}

Scene openFloor() {
    Scene s;
    MeshBuilder b(s);
    int floor = b.material("floor", glm::vec3(0.8f), 1.0f);
    b.quad(floor, {-2, 0, 2}, {4, 0, 0}, {0, 0, -4});
    s.finalize();
    return s;
}

Scene closedRoom(float white, glm::vec3 left, glm::vec3 right) {
    Scene s;
    MeshBuilder b(s);
    int w = b.material("white", glm::vec3(white), 1.0f);
    int l = b.material("left", left, 1.0f);
    int r = b.material("right", right, 1.0f);
    b.quad(w, {-2, 0, 2}, {4, 0, 0}, {0, 0, -4});  // floor
    b.quad(w, {-2, 3, -2}, {4, 0, 0}, {0, 0, 4});  // ceiling
    b.quad(w, {-2, 0, -2}, {4, 0, 0}, {0, 3, 0});  // back
    b.quad(w, {2, 0, 2}, {-4, 0, 0}, {0, 3, 0});   // front
    b.quad(l, {-2, 0, 2}, {0, 0, -4}, {0, 3, 0});  // left
    b.quad(r, {2, 0, -2}, {0, 0, 4}, {0, 3, 0});   // right
    s.finalize();
    return s;
}

LightSettings pointLight(glm::vec3 position, float intensity) {
    LightSettings l;
    l.type = LightType::Point;
    l.position = position;
    l.intensity = intensity;
    return l;
}

Scene box(glm::vec3 centre, glm::vec3 half, float yawDeg, float albedo) {
    Scene s;
    MeshBuilder b(s);
    int m = b.material("box", glm::vec3(albedo), 1.0f);
    b.box(m, centre, half, yawDeg);
    s.finalize();
    return s;
}

Scene scaledBuiltinScene(const std::string& name, float scale) {
    Scene s = makeBuiltinScene(name);
    for (Vertex& v : s.vertices) v.position *= scale;
    s.finalize();
    return s;
}

void scaleCamera(CameraSettings& camera, float scale) {
    camera.eye *= scale;
    camera.target *= scale;
    camera.near *= scale;
    camera.far *= scale;
}

Scene closedBox() { return box({0.0f, 0.5f, 0.0f}, {2.0f, 0.5f, 2.0f}, 0.0f, 0.8f); }

FrameSettings skyFrame(const Scene& scene, const std::string& technique) {
    Preset p;
    p.header.technique.name = technique;
    p.environment.enabled = true;
    p.environment.file = "builtin:constant";
    p.environment.cubeSize = 32;
    p.environment.samples = 16;
    FrameSettings fs = frameSettings(p, scene, 32, 32);
    fs.lights.clear();
    fs.camera.eye = {0.0f, 0.6f, 0.0f};
    fs.camera.target = {0.0f, 0.0f, 0.0f};
    fs.camera.up = {0.0f, 0.0f, -1.0f};
    fs.camera.fovY = 20.0f;
    return fs;
}

std::unique_ptr<Renderer> renderedAfresh(const Scene& scene, FrameSettings fs) {
    fs.render.keepStaticWork = false;
    auto r = std::make_unique<Renderer>();
    r->setScene(scene);
    r->render(fs);
    return r;
}

double meanIndirect(Renderer& r, const FrameSettings& fs) {
    r.render(fs);
    std::vector<float> px = r.readIndirectRadiance();
    if (const char* dir = std::getenv("GI_TEST_IMAGES"); dir && *dir) {
        // The image each measurement averaged, numbered in the order the test takes them.
        static std::string test;
        static int count = 0;
        std::string name = currentTestName();
        count = name == test ? count + 1 : 0;
        test = name;
        std::filesystem::create_directories(dir);
        writeEXR(std::filesystem::path(dir) / (name + "_" + std::to_string(count) + ".exr"), fs.width, fs.height, px);
    }
    return meanLuminance(imageFromGL(fs.width, fs.height, px));
}

double referenceOneBounceIndirect(const Scene& scene, const FrameSettings& fs, bool* cached) {
    ReferenceSettings rs;
    rs.spp = 256;
    rs.maxBounces = 2;
    rs.mode = ReferenceMode::Indirect;
    CachedReference ref = cachedReference(scene, fs, rs);
    if (cached) *cached = ref.fromCache;
    return meanLuminance(ref.image);
}


CommandResult runCommand(const std::string& command) {
    CommandResult r;
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
    if (!pipe) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe.get())) > 0) r.output.append(buf.data(), n);
    int status = pclose(pipe.release());
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

void GLTest::SetUp() {
    context();
    mErrorsBefore = gl::debugErrorCount();
}

void GLTest::TearDown() { EXPECT_EQ(gl::debugErrorCount(), mErrorsBefore) << "GL debug output reported errors"; }

}  // namespace gi::test
