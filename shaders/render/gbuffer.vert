// G-buffer pass: the scene is stored in world space, so only the view-projection applies.
#include "render/render_shared.h"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;
layout(location = 3) in vec4 aTangent;
layout(location = 4) in vec2 aUV1;

out vec3 vNormal;
out vec4 vTangent;
out vec2 vUV;
out vec2 vUV1;
// The depth pre-pass (depth.frag) and the G-buffer pass compare depths for equality.
invariant gl_Position;

void main() {
    vNormal = aNormal;
    vTangent = aTangent;
    vUV = aUV;
    vUV1 = aUV1;
    gl_Position = uRender.viewProj * vec4(aPosition, 1.0);
}
