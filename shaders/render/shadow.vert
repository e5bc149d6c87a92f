// Shadow pass: world-space scene into the light's clip space.
#include "render/render_shared.h"

layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec2 aUV;
layout(location = 4) in vec2 aUV1;

out vec3 vWorld;
out vec2 vUV;
out vec2 vUV1;

void main() {
    vWorld = aPosition;
    vUV = aUV;
    vUV1 = aUV1;
    gl_Position = uRender.viewProj * vec4(aPosition, 1.0);
}
