// Builds procedural meshes (quads, boxes, spheres) into a Scene: the built-in scenes and the
// tests' scenes are made with it.
#pragma once

#include "gi/scene/scene.h"

namespace gi {

class MeshBuilder {
public:
    explicit MeshBuilder(Scene& s) : mScene(s) {}

    int material(const std::string& name, glm::vec3 color, float roughness = 0.8f, int texture = -1);
    // A quad with corners p0, p0+u, p0+u+v, p0+v; the normal is normalize(cross(u, v)).
    void quad(int mat, glm::vec3 p0, glm::vec3 u, glm::vec3 v, glm::vec2 uvScale = glm::vec2(1.0f));
    // An axis-aligned box of half size h, rotated by `yawDeg` about +y, centred at `center`.
    void box(int mat, glm::vec3 center, glm::vec3 h, float yawDeg);
    void sphere(int mat, glm::vec3 center, float r, int slices = 48, int stacks = 24);

private:
    Scene& mScene;
    void add(int mat, const std::vector<uint32_t>& idx);
};

}  // namespace gi
