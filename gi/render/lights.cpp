#include "gi/render/lights.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

namespace gi {

light::GPULight packLight(const LightSettings& l) {
    light::GPULight g{};
    g.color = glm::vec4(l.color * l.intensity, 0.0f);
    g.position = glm::vec4(l.position, l.range);
    g.direction = glm::vec4(light::lightDirection(l.direction), 0.0f);
    g.spot = glm::vec4(light::spotCosines(l.innerConeDeg, l.outerConeDeg), 0.0f, 0.0f);
    g.info = glm::ivec4(int(l.type), l.castShadows ? 1 : 0, 0, 0);
    g.shadowViewProj = glm::mat4(1.0f);
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
    float radius = std::max(0.5f * glm::length(b.extent()), 1e-3f);
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

void LightBuffer::upload(const std::vector<LightSettings>& lights, const Bounds& sceneBounds, int shadowSize) {
    mLights.clear();
    for (const LightSettings& l : lights) {
        light::GPULight g = packLight(l);
        setShadowProjection(g, l, sceneBounds, shadowSize);
        mLights.push_back(g);
    }
    // Never empty: a buffer needs storage to be bound, and passes read none of it then.
    size_t count = std::max<size_t>(mLights.size(), 1);
    if (count > mCapacity) {
        mBuffer = gl::createBuffer(count * sizeof(light::GPULight), nullptr, GL_DYNAMIC_STORAGE_BIT);
        mCapacity = count;
    }
    if (!mLights.empty())
        glNamedBufferSubData(mBuffer.id(), 0, GLsizeiptr(mLights.size() * sizeof(light::GPULight)), mLights.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, light::kLightBufferBinding, mBuffer.id());
}

}  // namespace gi
