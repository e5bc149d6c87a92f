#include "gi/render/light_uniforms.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace gi {

void setLightBatchUniforms(const gl::Program& p, int i, const LightSettings& l, const ShadowMapView& sm, GLuint unit2D,
                           GLuint unitCube) {
    std::string k = "[" + std::to_string(i) + "]";
    auto set = [&](const char* name, const auto& value) { p.set((name + k).c_str(), value); };
    glm::vec3 dir = glm::length(l.direction) > 1e-8f ? glm::normalize(l.direction) : glm::vec3(0, -1, 0);
    set("uLightType", int(l.type));
    set("uLightColor", l.color * l.intensity);
    set("uLightPos", l.position);
    set("uLightDir", dir);
    set("uLightRange", l.range);
    set("uLightCos", glm::vec2(std::cos(glm::radians(std::min(l.innerConeDeg, l.outerConeDeg))),
                               std::cos(glm::radians(std::min(l.outerConeDeg, 90.0f)))));
    set("uShadowed", sm.depth ? 1 : 0);
    set("uShadowViewProj", sm.viewProj);
    set("uShadowFar", sm.far);
    if (sm.depth) glBindTextureUnit((sm.cube ? unitCube : unit2D) + GLuint(i), sm.depth);
}

}  // namespace gi
