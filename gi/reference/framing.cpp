#include "gi/reference/framing.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace gi {

namespace {

// The frame is fitted and scored as a square: the window's aspect is not known when the scene
// loads, and a square's fit still holds vertically in any wider frame.
constexpr float kAspect = 1.0f;

// What a view's primary rays meet: fractions of all rays.
struct ViewScore {
    float front = 0.0f;  // a surface seen from the side its normal faces
    float back = 0.0f;   // a surface seen from behind
    float hits() const { return front + back; }
    bool acceptable() const { return front >= 0.2f && back <= 0.05f * hits(); }
    float value() const { return front - 4.0f * back; }
};

bool seesFront(const PathTracer::SurfaceHit& h, const glm::vec3& dir) { return glm::dot(h.normal, dir) < 0.0f; }

ViewScore scoreView(const PathTracer& tracer, const CameraSettings& c, float tnear) {
    glm::vec3 f = glm::normalize(c.target - c.eye);
    glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
    glm::vec3 u = glm::cross(r, f);
    float ty = std::tan(glm::radians(c.fovY) * 0.5f), tx = ty * kAspect;
    constexpr int kW = 24, kH = 24;
    ViewScore s;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float sx = ((float(x) + 0.5f) / kW * 2.0f - 1.0f) * tx;
            float sy = ((float(y) + 0.5f) / kH * 2.0f - 1.0f) * ty;
            glm::vec3 d = glm::normalize(f + sx * r + sy * u);
            PathTracer::SurfaceHit h = tracer.nearestSurface(c.eye, d, tnear);
            if (h.t < 0.0f) continue;
            (seesFront(h, d) ? s.front : s.back) += 1.0f / (kW * kH);
        }
    return s;
}

// Directions spread evenly over the sphere (a Fibonacci lattice).
glm::vec3 sphereDirection(int i, int n) {
    float z = 1.0f - (float(i) + 0.5f) * 2.0f / float(n);
    float rho = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float phi = float(i) * glm::pi<float>() * (3.0f - std::sqrt(5.0f));
    return {rho * std::cos(phi), z, rho * std::sin(phi)};
}

}  // namespace

Framing frameScene(const Scene& scene, const PathTracer& tracer) {
    Framing out;
    out.camera = frameBounds(scene.bounds);
    out.how = "from outside, along a diagonal (not enclosed";
    if (!scene.bounds.valid() || scene.triangleCount() == 0) return out;
    const glm::vec3 center = scene.bounds.center(), extent = scene.bounds.extent();
    const float radius = scene.bounds.radius();
    const float tnear = radius * 1e-4f;

    // 1. Is the centre inside an enclosure?
    constexpr int kDirections = 256;
    int front = 0, back = 0;
    for (int i = 0; i < kDirections; ++i) {
        glm::vec3 d = sphereDirection(i, kDirections);
        PathTracer::SurfaceHit h = tracer.nearestSurface(center, d, tnear);
        if (h.t >= 0.0f) ++(seesFront(h, d) ? front : back);
    }
    char line[200];
    std::snprintf(line, sizeof line, "from its centre %d %% of directions meet fronts, %d %% backs",
                  front * 100 / kDirections, back * 100 / kDirections);
    if (front < kDirections * 60 / 100 || back > kDirections * 20 / 100) {
        out.how += std::string(": ") + line + ")";
        return out;
    }

    // 2. One view along each horizontal axis.
    struct Candidate {
        CameraSettings camera;
        bool open = false;  // nothing behind the eye: it stands outside an open side
        float room = 0.0f;  // distance from the centre to the eye
        const char* axis = "";
    };
    const float ty = std::tan(glm::radians(out.camera.fovY) * 0.5f);
    std::vector<Candidate> candidates;
    const struct {
        glm::vec3 d;
        const char* name;
    } axes[] = {{{0, 0, -1}, "-z"}, {{0, 0, 1}, "+z"}, {{-1, 0, 0}, "-x"}, {{1, 0, 0}, "+x"}};
    for (const auto& a : axes) {
        bool alongZ = a.d.z != 0.0f;
        float halfDepth = 0.5f * (alongZ ? extent.z : extent.x), halfWidth = 0.5f * (alongZ ? extent.x : extent.z);
        // 5 % of margin around the cross-section.
        float fit = 1.05f * std::max(0.5f * extent.y / ty, halfWidth / (ty * kAspect));
        Candidate c;
        c.camera = out.camera;  // frameBounds' field of view, up and near plane
        c.axis = a.name;
        PathTracer::SurfaceHit behind = tracer.nearestSurface(center, -a.d, tnear);
        c.open = behind.t < 0.0f;
        c.room = c.open ? halfDepth + fit : std::min(halfDepth + fit, 0.9f * behind.t);
        c.camera.eye = center - a.d * c.room;
        c.camera.target = center;
        c.camera.far = (c.room + radius) * 1.5f;
        candidates.push_back(c);
    }
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        return a.open != b.open ? a.open : a.room > b.room;
    });

    // 3. The first acceptable view, else the best.
    int best = -1;
    ViewScore bestScore;
    for (size_t i = 0; i < candidates.size(); ++i) {
        ViewScore s = scoreView(tracer, candidates[i].camera, tnear);
        if (s.acceptable()) {
            best = int(i);
            bestScore = s;
            break;
        }
        if (best < 0 || s.value() > bestScore.value()) {
            best = int(i);
            bestScore = s;
        }
    }
    const Candidate& c = candidates[size_t(best)];
    out.camera = c.camera;
    out.inside = true;
    char view[200];
    std::snprintf(view, sizeof view, "looking along %s from %s (%d %% of the frame on fronts, %d %% on backs; enclosed: ",
                  c.axis, c.open ? "outside its open side" : "inside", int(bestScore.front * 100.0f),
                  int(bestScore.back * 100.0f));
    out.how = std::string(view) + line + ")";
    return out;
}

std::string frameCameraless(Scene& scene) {
    if (!scene.framedCamera || scene.cameras.empty()) return "";
    PathTracer tracer(scene);
    Framing f = frameScene(scene, tracer);
    scene.cameras[0] = f.camera;
    if (f.inside) scene.cameraNames = {"inside the scene (the file has no camera)"};
    return f.how;
}

}  // namespace gi
