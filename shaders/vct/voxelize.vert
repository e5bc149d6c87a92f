// Voxelization, vertex stage: the scene is stored in world space; the geometry stage projects.
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
}
