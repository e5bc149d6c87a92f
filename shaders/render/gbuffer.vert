// G-buffer pass: the scene is stored in world space, so only the view-projection applies.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;

uniform mat4 uViewProj;

out vec3 vNormal;
out vec2 vUV;

void main() {
    vNormal = aNormal;
    vUV = aUV;
    gl_Position = uViewProj * vec4(aPosition, 1.0);
}
