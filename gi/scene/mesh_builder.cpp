#include "gi/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace gi {

int MeshBuilder::material(const std::string& name, glm::vec3 color, float roughness, int texture) {
    Material m;
    m.name = name;
    m.baseColor = glm::vec4(color, 1.0f);
    m.roughness = roughness;
    m.baseColorTexture = texture;
    mScene.materials.push_back(m);
    return int(mScene.materials.size()) - 1;
}

void MeshBuilder::quad(int mat, glm::vec3 p0, glm::vec3 u, glm::vec3 v, glm::vec2 uvScale) {
    glm::vec3 n = glm::normalize(glm::cross(u, v));
    uint32_t base = uint32_t(mScene.vertices.size());
    mScene.vertices.push_back({p0, n, {0, 0}});
    mScene.vertices.push_back({p0 + u, n, {uvScale.x, 0}});
    mScene.vertices.push_back({p0 + u + v, n, uvScale});
    mScene.vertices.push_back({p0 + v, n, {0, uvScale.y}});
    add(mat, {base, base + 1, base + 2, base, base + 2, base + 3});
}

void MeshBuilder::box(int mat, glm::vec3 center, glm::vec3 h, float yawDeg) {
    glm::mat4 m = glm::rotate(glm::translate(glm::mat4(1.0f), center), glm::radians(yawDeg), glm::vec3(0, 1, 0));
    auto P = [&](float x, float y, float z) { return glm::vec3(m * glm::vec4(x * h.x, y * h.y, z * h.z, 1.0f)); };
    auto D = [&](float x, float y, float z) { return glm::vec3(m * glm::vec4(x * h.x, y * h.y, z * h.z, 0.0f)); };
    quad(mat, P(-1, -1, 1), D(2, 0, 0), D(0, 2, 0));    // +z
    quad(mat, P(1, -1, -1), D(-2, 0, 0), D(0, 2, 0));   // -z
    quad(mat, P(1, -1, 1), D(0, 0, -2), D(0, 2, 0));    // +x
    quad(mat, P(-1, -1, -1), D(0, 0, 2), D(0, 2, 0));   // -x
    quad(mat, P(-1, 1, 1), D(2, 0, 0), D(0, 0, -2));    // +y
    quad(mat, P(-1, -1, -1), D(2, 0, 0), D(0, 0, 2));   // -y
}

void MeshBuilder::sphere(int mat, glm::vec3 center, float r, int slices, int stacks) {
    uint32_t base = uint32_t(mScene.vertices.size());
    for (int i = 0; i <= stacks; ++i) {
        float theta = float(M_PI) * float(i) / float(stacks);
        for (int j = 0; j <= slices; ++j) {
            float phi = 2.0f * float(M_PI) * float(j) / float(slices);
            glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            mScene.vertices.push_back({center + r * n, n, {float(j) / slices, float(i) / stacks}});
        }
    }
    std::vector<uint32_t> idx;
    for (int i = 0; i < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            uint32_t a = base + i * (slices + 1) + j, b = a + slices + 1;
            if (i != 0) idx.insert(idx.end(), {a, a + 1, b});
            if (i != stacks - 1) idx.insert(idx.end(), {a + 1, b + 1, b});
        }
    add(mat, idx);
}

void MeshBuilder::add(int mat, const std::vector<uint32_t>& idx) {
    uint32_t first = uint32_t(mScene.indices.size());
    mScene.indices.insert(mScene.indices.end(), idx.begin(), idx.end());
    mScene.draws.push_back({first, uint32_t(idx.size()), mat});
}

}  // namespace gi
