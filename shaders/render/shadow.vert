// Shadow pass: world-space scene into the light's clip space.
#include "render/render_shared.h"

layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec2 aUV;

out vec3 vWorld;
out vec2 vUV;

void main() {
    vWorld = aPosition;
    vUV = aUV;
    gl_Position = uRender.viewProj * vec4(aPosition, 1.0);
}
