// G-buffer pass: the scene is stored in world space, so only the view-projection applies.
#include "render/render_shared.h"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;

out vec3 vNormal;
out vec2 vUV;

void main() {
    vNormal = aNormal;
    vUV = aUV;
    gl_Position = uRender.viewProj * vec4(aPosition, 1.0);
}
