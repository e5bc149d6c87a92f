#include "gi/render/lights.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

namespace gi {

glm::vec3 emissionScale(const LightSettings& l) { return l.color * l.intensity; }

light::GPULight packLight(const LightSettings& l, const Emitter* emitter, int firstTriangle) {
    light::GPULight g{};
    g.color = glm::vec4(l.color * l.intensity, 0.0f);
    g.position = glm::vec4(l.position, l.range);
    g.direction = glm::vec4(light::lightDirection(l.direction), 0.0f);
    g.spot = glm::vec4(light::spotCosines(l.innerConeDeg, l.outerConeDeg), 0.0f, 0.0f);
    g.info = glm::ivec4(int(l.type), l.castShadows ? 1 : 0, 0, 0);
    g.shadowViewProj = glm::mat4(1.0f);
    if (l.type == LightType::Area) {
        // colour: the mean radiance, so colour x area x cos / d^2 is the light seen from afar.
        g.spot = glm::vec4(0.0f);
        g.color = glm::vec4(0.0f);
        if (emitter && emitter->area > 0.0f) {
            g.color = glm::vec4(emissionScale(l) * emitter->power / emitter->area, 0.0f);
            g.spot = glm::vec4(emitter->area, std::sqrt(emitter->area / shared::kPi), emitter->doubleSided ? 1.0f : 0.0f, 0.0f);
            g.info.z = firstTriangle;
            g.info.w = int(emitter->triangles.size());
        }
    }
    return g;
}

glm::mat4 spotViewProj(const glm::vec3& position, const glm::vec3& dir, float fovDeg, float far) {
    glm::mat4 view = glm::lookAt(position, position + dir, light::shadowUp(dir));
    glm::mat4 proj = glm::perspective(glm::radians(fovDeg), 1.0f, far * light::kShadowNearRatio, far);
    return proj * view;
}

glm::mat4 cubeFaceViewProj(const glm::vec3& position, int face, float far) {
    // Face orientations as GL defines them (+X, -X, +Y, -Y, +Z, -Z).
    static const glm::vec3 dirs[kCubeFaceCount] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const glm::vec3 ups[kCubeFaceCount] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, far * light::kShadowNearRatio, far);
    return proj * glm::lookAt(position, position + dirs[face], ups[face]);
}

void setShadowProjection(light::GPULight& g, const LightSettings& l, const Bounds& b, int size) {
    glm::vec3 center = b.center();
    const float radius = b.radius();
    glm::vec3 dir(g.direction);
    if (l.type == LightType::Directional) {
        glm::mat4 view = glm::lookAt(center - dir * radius * 2.0f, center, light::shadowUp(dir));
        glm::mat4 proj = glm::ortho(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f);
        g.shadowViewProj = proj * view;
        g.shadow = glm::vec4(radius * 3.5f, light::orthoTexel(radius, size), 0.0f, 0.0f);
        return;
    }
    float far = light::shadowFar(glm::length(l.position - center) + radius, l.range);
    if (l.type == LightType::Spot) {
        float fov = light::spotShadowFovDeg(l.outerConeDeg);
        g.shadowViewProj = spotViewProj(l.position, dir, fov, far);
        g.shadow = glm::vec4(far, light::perspectiveTexel(fov, size), 0.0f, 0.0f);
    } else {
        g.shadow = glm::vec4(far, light::cubeTexel(size), 0.0f, 0.0f);
    }
}

void bindBatchShadowMap(int i, const ShadowMapView& sm, GLuint unit2D, GLuint unitCube) {
    if (sm.depth) glBindTextureUnit((sm.cube ? unitCube : unit2D) + GLuint(i), sm.depth);
}

namespace {
// Uploads `data` into `buffer` (grown to at least one entry, so it can be bound) and binds it.
template <class T>
void uploadStorage(gl::Buffer& buffer, size_t& capacity, const std::vector<T>& data, GLuint binding) {
    size_t count = std::max<size_t>(data.size(), 1);
    if (count > capacity) {
        buffer = gl::createBuffer(count * sizeof(T), nullptr, GL_DYNAMIC_STORAGE_BIT);
        capacity = count;
    }
    if (!data.empty()) glNamedBufferSubData(buffer.id(), 0, GLsizeiptr(data.size() * sizeof(T)), data.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer.id());
}
}  // namespace

void LightBuffer::upload(const std::vector<LightSettings>& lights, const std::vector<Emitter>& emitters,
                         const Bounds& sceneBounds, int shadowSize) {
    mLights.clear();
    mTriangles.clear();
    mScales.assign(std::max<size_t>(emitters.size(), 1), glm::vec4(0.0f));
    for (const LightSettings& l : lights) {
        const Emitter* e = nullptr;
        if (l.type == LightType::Area && l.emitter >= 0 && size_t(l.emitter) < emitters.size()) e = &emitters[size_t(l.emitter)];
        light::GPULight g = packLight(l, e, int(mTriangles.size()));
        setShadowProjection(g, l, sceneBounds, shadowSize);
        mLights.push_back(g);
        if (!e) continue;
        glm::vec3 scale = emissionScale(l);
        mScales[size_t(l.emitter)] = glm::vec4(scale, 0.0f);
        for (size_t t = 0; t < e->triangles.size(); ++t) {
            light::GPUAreaTriangle tri;
            tri.p0 = glm::vec4(e->corners[3 * t], 0.0f);
            tri.p1 = glm::vec4(e->corners[3 * t + 1], 0.0f);
            tri.p2 = glm::vec4(e->corners[3 * t + 2], 0.0f);
            tri.radiance = glm::vec4(e->radiance[t] * scale, 0.0f);
            mTriangles.push_back(tri);
        }
    }
    uploadStorage(mTriangleBuffer, mTriangleCapacity, mTriangles, light::kAreaTriangleBinding);
    uploadStorage(mScaleBuffer, mScaleCapacity, mScales, light::kEmitterScaleBinding);
    // Never empty: a buffer needs storage to be bound, and passes read none of it then.
    uploadStorage(mBuffer, mCapacity, mLights, light::kLightBufferBinding);
}

light::GPULightWithTriangles LightBuffer::withTriangles(size_t i) const {
    light::GPULightWithTriangles b{};
    b.light = mLights[i];
    const glm::ivec4 info = b.light.info;
    if (info.x == light::kLightArea && info.w <= light::kAreaMaxExactTriangles)
        for (int t = 0; t < info.w; ++t) b.triangles[t] = mTriangles[size_t(info.z + t)];
    return b;
}

}  // namespace gi
