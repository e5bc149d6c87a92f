// Reflective shadow map: the world-space scene seen from the light.
#include "lpv/lpv_shared.h"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;

out vec3 vWorld;
out vec3 vNormal;
out vec2 vUV;

void main() {
    vWorld = aPosition;
    vNormal = aNormal;
    vUV = aUV;
    gl_Position = uLPV.lightViewProj * vec4(aPosition, 1.0);
}
