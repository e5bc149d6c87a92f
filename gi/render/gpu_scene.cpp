#include "gi/render/gpu_scene.h"

#include "common/light.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gi {

GPUScene::GPUScene(const Scene& scene)
    : mDraws(scene.draws), mMaterials(scene.materials), mEmitters(scene.emitters), mBounds(scene.bounds), mFreePath(meanFreePath(scene)) {
    static uint64_t sCount = 0;
    mId = ++sCount;
    mVertices = gl::createBuffer(scene.vertices.size() * sizeof(Vertex), scene.vertices.data());
    mIndices = gl::createBuffer(scene.indices.size() * sizeof(uint32_t), scene.indices.data());
    std::vector<int> emitterOf = scene.triangleEmitter;
    emitterOf.resize(std::max<size_t>(scene.triangleCount(), 1), -1);
    mTriangleEmitter = gl::createBuffer(emitterOf.size() * sizeof(int), emitterOf.data());
    mBytes = scene.vertices.size() * sizeof(Vertex) + scene.indices.size() * sizeof(uint32_t) + emitterOf.size() * sizeof(int);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    mVAO = gl::VertexArray(vao);
    glVertexArrayVertexBuffer(vao, 0, mVertices.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, mIndices.id());
    // Attribute locations 0..4 as the scene shaders declare them: position, normal, uv, tangent, uv1.
    const GLuint offsets[5] = {offsetof(Vertex, position), offsetof(Vertex, normal), offsetof(Vertex, uv), offsetof(Vertex, tangent),
                               offsetof(Vertex, uv1)};
    const GLint sizes[5] = {3, 3, 2, 4, 2};
    for (GLuint a = 0; a < 5; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
        glVertexArrayAttribBinding(vao, a, 0);
    }
    // Clusters: runs of kClusterTriangles triangles of each draw, with their bounds.
    mClusterFirst.push_back(0);
    for (const Draw& d : mDraws) {
        for (uint32_t i = 0; i < d.indexCount; i += kClusterTriangles * 3) {
            Cluster k;
            k.firstIndex = d.firstIndex + i;
            k.indexCount = std::min(d.indexCount - i, kClusterTriangles * 3);
            k.min = glm::vec3(std::numeric_limits<float>::max());
            k.max = glm::vec3(-std::numeric_limits<float>::max());
            for (uint32_t j = k.firstIndex; j < k.firstIndex + k.indexCount; ++j) {
                const glm::vec3& p = scene.vertices[scene.indices[j]].position;
                k.min = glm::min(k.min, p);
                k.max = glm::max(k.max, p);
            }
            mClusters.push_back(k);
        }
        mClusterFirst.push_back(uint32_t(mClusters.size()));
    }
    for (const Texture& t : scene.textures) {
        int levels = 1 + int(std::floor(std::log2(std::max(t.width, t.height))));
        // Colour (base colour, emission) is sRGB, data maps (metallic-roughness, occlusion, normal) linear.
        gl::Texture tex = gl::Texture::create2D(t.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t.width, t.height, levels);
        glTextureSubImage2D(tex.id(), 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
        glGenerateTextureMipmap(tex.id());
        mBytes += tex.bytes();
        mTextures.push_back(std::move(tex));
    }
}

bool GPUScene::outside(const glm::mat4& viewProj, const Cluster& k) {
    // Clip-space corners; the box is outside when every corner fails the same plane
    // (-w <= x, y, z <= w), a test that holds for corners behind the eye too.
    int out[6] = {0, 0, 0, 0, 0, 0};
    for (int c = 0; c < 8; ++c) {
        glm::vec3 p((c & 1) ? k.max.x : k.min.x, (c & 2) ? k.max.y : k.min.y, (c & 4) ? k.max.z : k.min.z);
        glm::vec4 q = viewProj * glm::vec4(p, 1.0f);
        for (int a = 0; a < 3; ++a) {
            out[2 * a] += q[a] < -q.w;
            out[2 * a + 1] += q[a] > q.w;
        }
    }
    for (int i = 0; i < 6; ++i)
        if (out[i] == 8) return true;
    return false;
}

void GPUScene::bindTriangleEmitters() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, light::kTriangleEmitterBinding, mTriangleEmitter.id());
}

size_t GPUScene::estimateBytes(const Scene& scene) {
    size_t bytes = scene.vertices.size() * sizeof(Vertex) + scene.indices.size() * sizeof(uint32_t) + scene.triangleCount() * sizeof(int);
    for (const Texture& t : scene.textures) bytes += t.rgba.size() * 4 / 3;  // the mip chain adds a third
    return bytes;
}

}  // namespace gi
