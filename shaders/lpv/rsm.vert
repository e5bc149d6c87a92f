// Reflective shadow map: the world-space scene seen from the light.
#include "lpv/lpv_shared.h"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;
layout(location = 3) in vec4 aTangent;
layout(location = 4) in vec2 aUV1;

out vec3 vWorld;
out vec3 vNormal;
out vec2 vUV;
out vec4 vTangent;
out vec2 vUV1;

void main() {
    vWorld = aPosition;
    vNormal = aNormal;
    vUV = aUV;
    vTangent = aTangent;
    vUV1 = aUV1;
    gl_Position = uLPV.lightViewProj * vec4(aPosition, 1.0);
}
