#include "gi/scene/emitters.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

namespace gi {

namespace {

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

int findRoot(std::vector<int>& parent, int i) {
    while (parent[size_t(i)] != i) {
        parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
        i = parent[size_t(i)];
    }
    return i;
}

struct Tri {
    uint32_t index;  // triangle index
    glm::vec3 p[3];  // front-wound
    glm::vec3 centre;
    float area;
    glm::vec3 radiance;  // the material's emission, its texture's mean over the triangle
};

// Mean emission of the material over triangle t: the emissive factor times the emissive
// texture's mean over kEmissionSamples stratified points (the exact factor without a texture).
constexpr int kEmissionSamplesPerSide = 4;
glm::vec3 meanEmission(const Scene& scene, const Material& m, uint32_t t) {
    if (m.emissiveTexture < 0) return m.emissive;
    const uint32_t* idx = &scene.indices[size_t(t) * 3];
    const Vertex& a = scene.vertices[idx[0]];
    const Vertex& b = scene.vertices[idx[1]];
    const Vertex& c = scene.vertices[idx[2]];
    glm::vec3 sum(0.0f);
    int n = 0;
    // Points of a regular grid over the unit square folded into the triangle.
    for (int j = 0; j < kEmissionSamplesPerSide; ++j)
        for (int i = 0; i < kEmissionSamplesPerSide; ++i) {
            float u = (float(i) + 0.5f) / kEmissionSamplesPerSide, v = (float(j) + 0.5f) / kEmissionSamplesPerSide;
            if (u + v > 1.0f) {
                u = 1.0f - u;
                v = 1.0f - v;
            }
            float w = 1.0f - u - v;
            sum += emission(scene, m, w * a.uv + u * b.uv + v * c.uv, w * a.uv1 + u * b.uv1 + v * c.uv1);
            ++n;
        }
    return sum / float(n);
}

// Splits `tris` (one connected surface) into parts of at most `most` triangles.
void split(std::vector<Tri> tris, size_t most, std::vector<std::vector<Tri>>& out) {
    if (tris.size() <= most) {
        out.push_back(std::move(tris));
        return;
    }
    Bounds b;
    for (const Tri& t : tris) b.grow(t.centre);
    glm::vec3 e = b.extent();
    int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    auto mid = tris.begin() + std::ptrdiff_t(tris.size() / 2);
    std::nth_element(tris.begin(), mid, tris.end(), [axis](const Tri& a, const Tri& c) {
        return std::tie(a.centre[axis], a.index) < std::tie(c.centre[axis], c.index);
    });
    split(std::vector<Tri>(tris.begin(), mid), most, out);
    split(std::vector<Tri>(mid, tris.end()), most, out);
}

}  // namespace

void buildEmitters(Scene& scene) {
    scene.emitters.clear();
    const size_t triCount = scene.triangleCount();
    scene.triangleEmitter.assign(triCount, -1);
    // The emissive triangles, front-wound by their vertex normals (the side the path tracer's
    // shading normal says they emit from).
    std::vector<Tri> tris;
    std::vector<int> triMaterial;
    for (const Draw& d : scene.draws) {
        const Material& m = scene.materials[size_t(d.material)];
        if (luminance(m.emissive) <= 0.0f) continue;
        for (uint32_t k = 0; k < d.indexCount / 3; ++k) {
            uint32_t t = d.firstIndex / 3 + k;
            const uint32_t* idx = &scene.indices[size_t(t) * 3];
            Tri tri;
            tri.index = t;
            for (int c = 0; c < 3; ++c) tri.p[c] = scene.vertices[idx[c]].position;
            glm::vec3 ng = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
            tri.area = 0.5f * glm::length(ng);
            if (!(tri.area > 0.0f)) continue;
            tri.radiance = meanEmission(scene, m, t);
            if (luminance(tri.radiance) <= 0.0f) continue;  // a dark part of an emissive texture
            glm::vec3 ns = scene.vertices[idx[0]].normal + scene.vertices[idx[1]].normal + scene.vertices[idx[2]].normal;
            if (glm::dot(ng, ns) < 0.0f) std::swap(tri.p[1], tri.p[2]);
            tri.centre = (tri.p[0] + tri.p[1] + tri.p[2]) / 3.0f;
            tris.push_back(tri);
            triMaterial.push_back(d.material);
        }
    }
    if (tris.empty()) return;

    // Connected surfaces: triangles of one material sharing a vertex position (welded to a grid
    // far finer than the scene).
    float cell = std::max(glm::length(scene.bounds.extent()), 1e-6f) * 1e-6f;
    std::vector<int> parent(tris.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::map<std::tuple<int, int64_t, int64_t, int64_t>, int> seen;
    for (size_t i = 0; i < tris.size(); ++i)
        for (const glm::vec3& p : tris[i].p) {
            glm::vec3 q = glm::round(p / cell);
            auto key = std::make_tuple(triMaterial[i], int64_t(q.x), int64_t(q.y), int64_t(q.z));
            auto [it, inserted] = seen.emplace(key, int(i));
            if (!inserted) parent[size_t(findRoot(parent, int(i)))] = findRoot(parent, it->second);
        }
    std::map<int, std::vector<Tri>> surfaces;  // by root, in triangle order
    for (size_t i = 0; i < tris.size(); ++i) surfaces[findRoot(parent, int(i))].push_back(tris[i]);

    // Parts of kMaxEmitterTriangles, or larger when the scene has more emissive triangles than
    // kMaxEmitters such parts hold (the lights then shade as points with a cosine lobe).
    size_t most = std::max<size_t>(kMaxEmitterTriangles, (tris.size() + kMaxEmitters - 1) / kMaxEmitters);
    std::vector<std::vector<Tri>> parts;
    std::vector<int> partMaterial;
    for (auto& [root, surface] : surfaces) {
        size_t before = parts.size();
        split(std::move(surface), most, parts);
        partMaterial.insert(partMaterial.end(), parts.size() - before, triMaterial[size_t(root)]);
    }

    std::vector<Emitter> emitters;
    std::map<int, int> perMaterial;
    for (size_t k = 0; k < parts.size(); ++k) {
        const Material& m = scene.materials[size_t(partMaterial[k])];
        Emitter e;
        e.material = partMaterial[k];
        e.doubleSided = m.doubleSided;
        glm::vec3 normal(0.0f);
        for (const Tri& t : parts[k]) {
            e.triangles.push_back(t.index);
            e.corners.insert(e.corners.end(), {t.p[0], t.p[1], t.p[2]});
            e.radiance.push_back(t.radiance);
            e.area += t.area;
            e.centroid += t.centre * t.area;
            e.power += t.radiance * t.area;
            normal += glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
        }
        e.centroid /= e.area;
        if (glm::length(normal) > 0.0f) e.normal = glm::normalize(normal);
        int n = perMaterial[e.material]++;
        e.name = m.name.empty() ? "material " + std::to_string(e.material) : m.name;
        if (n > 0) e.name += "#" + std::to_string(n);
        emitters.push_back(std::move(e));
    }
    if (emitters.size() > size_t(kMaxEmitters)) {
        std::stable_sort(emitters.begin(), emitters.end(),
                         [](const Emitter& a, const Emitter& b) { return luminance(a.power) > luminance(b.power); });
        scene.warnings.push_back(std::to_string(emitters.size()) + " emissive surfaces: the " +
                                 std::to_string(emitters.size() - size_t(kMaxEmitters)) +
                                 " faintest emit nothing (at most " + std::to_string(kMaxEmitters) + " area lights)");
        emitters.resize(size_t(kMaxEmitters));
    }
    for (size_t k = 0; k < emitters.size(); ++k)
        for (uint32_t t : emitters[k].triangles) scene.triangleEmitter[t] = int(k);
    scene.emitters = std::move(emitters);
}

std::vector<LightSettings> sceneLights(const Scene& scene) {
    std::vector<LightSettings> lights = scene.lights;
    std::vector<size_t> order(scene.emitters.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return luminance(scene.emitters[a].power) > luminance(scene.emitters[b].power);
    });
    std::vector<bool> shadowed(scene.emitters.size(), false);
    for (size_t i = 0; i < order.size() && i < size_t(kShadowedEmitters); ++i) shadowed[order[i]] = true;
    for (size_t k = 0; k < scene.emitters.size(); ++k) {
        LightSettings l;
        l.type = LightType::Area;
        l.emitter = int(k);
        l.intensity = 1.0f;
        l.castShadows = shadowed[k];
        lights.push_back(placeAreaLight(l, scene.emitters[k]));
    }
    return lights;
}

LightSettings placeAreaLight(LightSettings l, const Emitter& e) {
    l.position = e.centroid;
    l.direction = e.normal;
    l.range = 0.0f;
    return l;
}

}  // namespace gi
