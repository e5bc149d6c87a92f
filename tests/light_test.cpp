// The one light model (shaders/common/light.h, gi/render/lights.h): the shared functions against
// hand-computed values, the GPULight layout in C++ and as the GL compiler lays it out, and the
// GPU's evaluation of the same functions on lights read from the light buffer.
#include "common/light.h"
#include "gi/gl/shader.h"
#include "gi/render/lights.h"
#include "test_util.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstddef>
#include <fstream>

namespace gi {
namespace {

using light::GPULight;

TEST(Light, RangeWindowIsOneAtTheLightAndZeroFromTheRangeOn) {
    EXPECT_EQ(light::rangeWindow(0.0f, 2.0f), 1.0f);
    // Half the range: (1 - 0.5^4)^2 = 0.9375^2.
    EXPECT_FLOAT_EQ(light::rangeWindow(1.0f, 2.0f), 0.87890625f);
    EXPECT_EQ(light::rangeWindow(2.0f, 2.0f), 0.0f);
    EXPECT_EQ(light::rangeWindow(3.0f, 2.0f), 0.0f);
    // Range 0 is infinite.
    EXPECT_EQ(light::rangeWindow(1e6f, 0.0f), 1.0f);
}

TEST(Light, SpotConeIsOneInsideZeroOutsideAndSmoothBetween) {
    glm::vec2 c = light::spotCosines(20.0f, 30.0f);
    EXPECT_FLOAT_EQ(c.x, 0.93969262f);  // cos 20
    EXPECT_FLOAT_EQ(c.y, 0.86602540f);  // cos 30
    EXPECT_EQ(light::spotCone(std::cos(glm::radians(10.0f)), c), 1.0f);
    EXPECT_EQ(light::spotCone(std::cos(glm::radians(40.0f)), c), 0.0f);
    // A quarter of the way from the outer to the inner cosine: 0.25^2 (3 - 2 * 0.25) = 0.15625.
    EXPECT_NEAR(light::spotCone(c.y + 0.25f * (c.x - c.y), c), 0.15625f, 1e-5f);
    EXPECT_NEAR(light::spotCone(0.5f * (c.x + c.y), c), 0.5f, 1e-5f);
    // Equal cones: a hard edge, not a division by zero.
    glm::vec2 hard = light::spotCosines(30.0f, 30.0f);
    EXPECT_EQ(light::spotCone(std::cos(glm::radians(29.9f)), hard), 1.0f);
    EXPECT_EQ(light::spotCone(std::cos(glm::radians(30.1f)), hard), 0.0f);
}

TEST(Light, OuterConeIsAtMostNinetyDegreesAndInnerAtMostOuter) {
    glm::vec2 c = light::spotCosines(30.0f, 120.0f);
    EXPECT_FLOAT_EQ(c.x, 0.86602540f);
    EXPECT_NEAR(c.y, 0.0f, 1e-6f);  // cos 90, not cos 120 = -0.5
    glm::vec2 wide = light::spotCosines(100.0f, 120.0f);
    EXPECT_NEAR(wide.x, 0.0f, 1e-6f);
    glm::vec2 swapped = light::spotCosines(40.0f, 30.0f);
    EXPECT_EQ(swapped.x, swapped.y);
    EXPECT_EQ(light::spotShadowFovDeg(30.0f), 62.0f);
    EXPECT_EQ(light::spotShadowFovDeg(120.0f), 170.0f);
}

TEST(Light, ZeroDirectionFallsBackToStraightDown) {
    EXPECT_EQ(light::lightDirection(glm::vec3(0.0f)), glm::vec3(0.0f, -1.0f, 0.0f));
    EXPECT_EQ(light::lightDirection(glm::vec3(1e-9f, 0.0f, 0.0f)), glm::vec3(0.0f, -1.0f, 0.0f));
    EXPECT_EQ(light::lightDirection(glm::vec3(0.0f, 0.0f, -2.0f)), glm::vec3(0.0f, 0.0f, -1.0f));
}

TEST(Light, FalloffIsInverseSquareTimesWindowTimesCone) {
    LightSettings s;
    s.type = LightType::Point;
    GPULight l = packLight(s);
    EXPECT_FLOAT_EQ(light::lightFalloff(l, 2.0f, 1.0f), 0.25f);
    s.range = 4.0f;
    l = packLight(s);
    EXPECT_FLOAT_EQ(light::lightFalloff(l, 2.0f, 1.0f), 0.25f * 0.87890625f);
    EXPECT_FLOAT_EQ(light::lightProfile(l, 2.0f, 1.0f), 0.87890625f);
    s.type = LightType::Spot;
    s.innerConeDeg = 20.0f;
    s.outerConeDeg = 30.0f;
    l = packLight(s);
    float mid = 0.5f * (l.spot.x + l.spot.y);
    EXPECT_NEAR(light::lightFalloff(l, 2.0f, mid), 0.25f * 0.87890625f * 0.5f, 1e-6f);
    EXPECT_EQ(light::lightFalloff(l, 2.0f, 0.5f), 0.0f);  // 60 degrees off the axis
}

TEST(Light, PackedLightHoldsTheModelsValues) {
    LightSettings s;
    s.type = LightType::Spot;
    s.color = {1.0f, 0.5f, 0.25f};
    s.intensity = 4.0f;
    s.position = {1.0f, 2.0f, 3.0f};
    s.direction = {0.0f, 0.0f, 0.0f};
    s.range = 7.0f;
    s.innerConeDeg = 10.0f;
    s.outerConeDeg = 95.0f;
    s.castShadows = false;
    GPULight l = packLight(s);
    EXPECT_EQ(l.color, glm::vec4(4.0f, 2.0f, 1.0f, 0.0f));
    EXPECT_EQ(l.position, glm::vec4(1.0f, 2.0f, 3.0f, 7.0f));
    EXPECT_EQ(l.direction, glm::vec4(0.0f, -1.0f, 0.0f, 0.0f));
    EXPECT_FLOAT_EQ(l.spot.x, std::cos(glm::radians(10.0f)));
    EXPECT_NEAR(l.spot.y, 0.0f, 1e-6f);
    EXPECT_EQ(l.info, glm::ivec4(shared::kLightSpot, 0, 0, 0));
}

TEST(Light, GPULightLayoutIsStd430) {
    EXPECT_EQ(sizeof(GPULight), 160u);
    EXPECT_EQ(offsetof(GPULight, color), 0u);
    EXPECT_EQ(offsetof(GPULight, position), 16u);
    EXPECT_EQ(offsetof(GPULight, direction), 32u);
    EXPECT_EQ(offsetof(GPULight, spot), 48u);
    EXPECT_EQ(offsetof(GPULight, shadow), 64u);
    EXPECT_EQ(offsetof(GPULight, info), 80u);
    EXPECT_EQ(offsetof(GPULight, shadowViewProj), 96u);
}

TEST(Light, ShadowParameters) {
    EXPECT_EQ(light::shadowFar(10.0f, 0.0f), 10.0f);
    EXPECT_EQ(light::shadowFar(10.0f, 4.0f), 4.0f);
    EXPECT_EQ(light::shadowFar(3.0f, 4.0f), 3.0f);
    EXPECT_NEAR(light::perspectiveTexel(90.0f, 512), 2.0f / 512.0f, 1e-7f);
    EXPECT_EQ(light::cubeTexel(512), 2.0f / 512.0f);
    EXPECT_FLOAT_EQ(light::orthoTexel(3.0f, 600), 0.01f);
    EXPECT_EQ(light::shadowUp({0.0f, -1.0f, 0.0f}), glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(light::shadowUp(glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f))), glm::vec3(0.0f, 1.0f, 0.0f));
}

// A point's normalised device coordinates under a view-projection.
glm::vec3 ndc(const glm::mat4& viewProj, const glm::vec3& p) {
    glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
    return glm::vec3(c) / c.w;
}

TEST(Light, SpotShadowFrustumIsTheOuterConePlusTheMarginCutAtTheRange) {
    Bounds b;
    b.grow({-5.0f, -5.0f, -5.0f});
    b.grow({5.0f, 5.0f, 5.0f});
    LightSettings s;
    s.type = LightType::Spot;
    s.position = {0.0f, 4.0f, 0.0f};
    s.direction = {0.0f, -2.0f, 0.0f};
    s.outerConeDeg = 30.0f;
    s.range = 6.0f;
    GPULight l = packLight(s);
    setShadowProjection(l, s, b, 256);
    EXPECT_EQ(l.shadow.x, 6.0f);  // the range, nearer than the scene's far side
    EXPECT_NEAR(l.shadow.y, 2.0f * std::tan(glm::radians(31.0f)) / 256.0f, 1e-7f);
    // On the axis: the map's centre; at the range: the far plane.
    glm::vec3 axis = ndc(l.shadowViewProj, {0.0f, 1.0f, 0.0f});
    EXPECT_NEAR(axis.x, 0.0f, 1e-5f);
    EXPECT_NEAR(axis.y, 0.0f, 1e-5f);
    EXPECT_NEAR(ndc(l.shadowViewProj, {0.0f, -2.0f, 0.0f}).z, 1.0f, 1e-4f);
    // 31 degrees off the axis (outer cone + margin): the map's edge.
    float off = 3.0f * std::tan(glm::radians(31.0f));
    glm::vec3 edge = ndc(l.shadowViewProj, {off, 1.0f, 0.0f});
    EXPECT_NEAR(std::abs(edge.x) + std::abs(edge.y), 1.0f, 1e-4f);

    s.type = LightType::Directional;
    s.direction = {0.3f, -1.0f, 0.2f};
    l = packLight(s);
    setShadowProjection(l, s, b, 256);
    // The orthographic box holds the scene's bounding sphere, so every corner of the bounds.
    for (int i = 0; i < 8; ++i) {
        glm::vec3 corner(i & 1 ? 5.0f : -5.0f, i & 2 ? 5.0f : -5.0f, i & 4 ? 5.0f : -5.0f);
        glm::vec3 p = ndc(l.shadowViewProj, corner);
        EXPECT_LE(std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))), 1.0f + 1e-5f) << i;
    }
    EXPECT_NEAR(l.shadow.y, 2.0f * 5.0f * std::sqrt(3.0f) / 256.0f, 1e-6f);
}

class LightGL : public test::GLTest {
protected:
    std::filesystem::path mDir;
    void SetUp() override {
        test::GLTest::SetUp();
        mDir = test::tempDir();
        std::filesystem::copy(std::filesystem::path(GI_SHADER_DIR) / "common", mDir / "common");
        setenv("GI_SHADER_DIR", mDir.c_str(), 1);
    }
    void TearDown() override {
        unsetenv("GI_SHADER_DIR");
        test::GLTest::TearDown();
    }
};

// The GPU evaluates the shared functions on lights it reads from the renderer's light buffer.
const char* kProbe = R"(#include "common/light.h"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };  // xyz: where, w: light index
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int uCount;
void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    GPULight l = uLights[int(points[i].w)];
    vec3 toLight = l.position.xyz - points[i].xyz;
    float dist = length(toLight);
    float cosAxis = dot(-toLight / max(dist, 1e-6), l.direction.xyz);
    results[i] = vec4(lightFalloff(l, dist, cosAxis), lightProfile(l, dist, cosAxis),
                      spotCone(cosAxis, vec2(l.spot)), rangeWindow(dist, l.position.w));
}
)";

TEST_F(LightGL, LightReadFromTheBufferOnTheGPUAgreesWithTheCPU) {
    std::ofstream(mDir / "probe.comp") << kProbe;
    gl::Program probe("light probe", {{GL_COMPUTE_SHADER, "probe.comp"}});

    std::vector<LightSettings> lights(4);
    lights[0].type = LightType::Point;
    lights[0].position = {0.0f, 2.0f, 0.0f};
    lights[1] = lights[0];
    lights[1].range = 2.5f;
    lights[2].type = LightType::Spot;
    lights[2].position = {0.5f, 2.0f, -0.5f};
    lights[2].direction = {0.2f, -1.0f, 0.1f};
    lights[2].innerConeDeg = 15.0f;
    lights[2].outerConeDeg = 40.0f;
    lights[3] = lights[2];
    lights[3].range = 3.0f;
    lights[3].outerConeDeg = 120.0f;  // clamped to 90
    Bounds b;
    b.grow(glm::vec3(-3.0f));
    b.grow(glm::vec3(3.0f));
    LightBuffer buffer;
    buffer.upload(lights, {}, b, 256);

    // Points on a grid under the lights, each with every light.
    std::vector<glm::vec4> points;
    for (int li = 0; li < int(lights.size()); ++li)
        for (int z = 0; z < 8; ++z)
            for (int x = 0; x < 8; ++x)
                points.push_back({-2.0f + 0.55f * float(x), 0.1f * float(z), -2.0f + 0.5f * float(z), float(li)});
    const int count = int(points.size());
    gl::Buffer in = gl::createBuffer(points.size() * sizeof(glm::vec4), points.data());
    gl::Buffer out = gl::createBuffer(points.size() * sizeof(glm::vec4), nullptr);
    probe.use();
    probe.set("uCount", count);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> gpu(points.size());
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(gpu.size() * sizeof(glm::vec4)), gpu.data());

    int lit = 0, windowed = 0, penumbra = 0;
    for (int i = 0; i < count; ++i) {
        const GPULight& l = buffer[size_t(points[i].w)];
        glm::vec3 toLight = glm::vec3(l.position) - glm::vec3(points[i]);
        float dist = glm::length(toLight);
        float cosAxis = glm::dot(-toLight / std::max(dist, 1e-6f), glm::vec3(l.direction));
        glm::vec4 cpu(light::lightFalloff(l, dist, cosAxis), light::lightProfile(l, dist, cosAxis),
                      light::spotCone(cosAxis, glm::vec2(l.spot)), light::rangeWindow(dist, l.position.w));
        // 1e-5, relative where the inverse square exceeds 1.
        for (int k = 0; k < 4; ++k)
            EXPECT_NEAR(gpu[size_t(i)][k], cpu[k], 1e-5f * std::max(1.0f, std::abs(cpu[k]))) << "point " << i << " value " << k;
        lit += cpu.x > 0.0f;
        windowed += cpu.w > 0.0f && cpu.w < 1.0f;
        penumbra += l.info.x == shared::kLightSpot && cpu.z > 0.0f && cpu.z < 1.0f;
    }
    // The points cover every case: lit, inside a range window, in a spot's penumbra.
    EXPECT_GT(lit, count / 4);
    EXPECT_GT(windowed, 10);
    EXPECT_GT(penumbra, 10);
}

TEST_F(LightGL, GLLaysGPULightOutAsCppDoes) {
    std::ofstream(mDir / "layout.comp") << R"(#include "common/light.h"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer O { vec4 o[]; };
void main() {
    GPULight l = uLights[0];
    o[0] = l.color + l.position + l.direction + l.spot + l.shadow + vec4(l.info) + l.shadowViewProj[0];
}
)";
    gl::Program p("light layout", {{GL_COMPUTE_SHADER, "layout.comp"}});
    auto query = [&](const char* name, GLenum property) {
        GLuint index = glGetProgramResourceIndex(p.id(), GL_BUFFER_VARIABLE, name);
        EXPECT_NE(index, GL_INVALID_INDEX) << name;
        GLint value = -1;
        glGetProgramResourceiv(p.id(), GL_BUFFER_VARIABLE, index, 1, &property, 1, nullptr, &value);
        return value;
    };
    EXPECT_EQ(query("uLights[0].color", GL_TOP_LEVEL_ARRAY_STRIDE), GLint(sizeof(GPULight)));
    EXPECT_EQ(query("uLights[0].color", GL_OFFSET), GLint(offsetof(GPULight, color)));
    EXPECT_EQ(query("uLights[0].position", GL_OFFSET), GLint(offsetof(GPULight, position)));
    EXPECT_EQ(query("uLights[0].direction", GL_OFFSET), GLint(offsetof(GPULight, direction)));
    EXPECT_EQ(query("uLights[0].spot", GL_OFFSET), GLint(offsetof(GPULight, spot)));
    EXPECT_EQ(query("uLights[0].shadow", GL_OFFSET), GLint(offsetof(GPULight, shadow)));
    EXPECT_EQ(query("uLights[0].info", GL_OFFSET), GLint(offsetof(GPULight, info)));
    EXPECT_EQ(query("uLights[0].shadowViewProj", GL_OFFSET), GLint(offsetof(GPULight, shadowViewProj)));
    EXPECT_EQ(query("uLights[0].shadowViewProj", GL_MATRIX_STRIDE), 16);
    GLuint block = glGetProgramResourceIndex(p.id(), GL_SHADER_STORAGE_BLOCK, "LightBuffer");
    ASSERT_NE(block, GL_INVALID_INDEX);
    const GLenum bindingProperty = GL_BUFFER_BINDING;
    GLint binding = -1;
    glGetProgramResourceiv(p.id(), GL_SHADER_STORAGE_BLOCK, block, 1, &bindingProperty, 1, nullptr, &binding);
    EXPECT_EQ(binding, light::kLightBufferBinding);
}

}  // namespace
}  // namespace gi
