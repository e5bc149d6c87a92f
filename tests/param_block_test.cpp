// Parameter blocks (gi/gl/uniform_block.h): the C++ structs of shaders/ssao/ssao_shared.h,
// shaders/envmap/envmap_shared.h, shaders/lpv/lpv_shared.h, shaders/volumetric/volumetric_shared.h,
// shaders/render/render_shared.h, shaders/vct/vct_shared.h and shaders/common/material_shared.h against the layout the driver gives
// the linked programs' blocks (size, each member's offset, array and matrix strides), a block laid out differently caught by
// that comparison, and a block a program names, binds or sizes differently from the host refused
// at construction, at reload and at a recompile, with the shader and the block in the message.
#include "gi/envmap/environment.h"
#include "gi/gl/uniform_block.h"
#include "gi/lpv/lpv.h"
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/scene.h"
#include "gi/ssao/ssao.h"
#include "gi/util/error.h"
#include "gi/vct/vct.h"
#include "gi/volumetric/volumetric.h"

#include "test_util.h"

#include <cstddef>
#include <fstream>
#include <map>
#include <sstream>
#include <type_traits>

namespace gi {
namespace {

using namespace shared;

// A member of a C++ parameter struct as GL names it: arrays by their first element.
struct Member {
    std::string name;
    size_t offset;
    size_t arrayStride;  // 0 for a member that is no array
};

template <class F>
Member member(const std::string& name, size_t offset) {
    if constexpr (std::is_array_v<F>) return {name + "[0]", offset, sizeof(std::remove_extent_t<F>)};
    else return {name, offset, 0};
}
#define GI_MEMBER(T, f) member<decltype(T::f)>(#f, offsetof(T, f))

std::vector<Member> ssaoMembers() {
    using T = SSAOParams;
    return {GI_MEMBER(T, sampleCount), GI_MEMBER(T, radius), GI_MEMBER(T, bias),   GI_MEMBER(T, blurRadius),
            GI_MEMBER(T, strength),    GI_MEMBER(T, pad0),   GI_MEMBER(T, pad1),   GI_MEMBER(T, pad2),
            GI_MEMBER(T, view),        GI_MEMBER(T, proj),   GI_MEMBER(T, invProj), GI_MEMBER(T, kernel),
            GI_MEMBER(T, noise)};
}

std::vector<Member> envMembers() {
    using T = EnvParams;
    return {GI_MEMBER(T, invViewProj), GI_MEMBER(T, eye),        GI_MEMBER(T, width),     GI_MEMBER(T, height),
            GI_MEMBER(T, intensity),   GI_MEMBER(T, rotation),   GI_MEMBER(T, mipCount),  GI_MEMBER(T, pad0),
            GI_MEMBER(T, pad1),        GI_MEMBER(T, pad2),       GI_MEMBER(T, mipRoughness), GI_MEMBER(T, size),
            GI_MEMBER(T, rowOffset),   GI_MEMBER(T, sourceSize), GI_MEMBER(T, mode),      GI_MEMBER(T, roughness),
            GI_MEMBER(T, diskRadius),  GI_MEMBER(T, samples),    GI_MEMBER(T, pad3),      GI_MEMBER(T, sh)};
}

std::vector<Member> lpvMembers() {
    using T = LPVParams;
    return {GI_MEMBER(T, invViewProj),   GI_MEMBER(T, lightViewProj),  GI_MEMBER(T, gridMinCell),
            GI_MEMBER(T, cameraPos),     GI_MEMBER(T, cascadeMinCell), GI_MEMBER(T, resolution),   GI_MEMBER(T, width),
            GI_MEMBER(T, height),        GI_MEMBER(T, lightIndex),     GI_MEMBER(T, texelArea),    GI_MEMBER(T, texelSolidAngle),
            GI_MEMBER(T, nudge),
            GI_MEMBER(T, fromGBuffer),   GI_MEMBER(T, stride),         GI_MEMBER(T, pixelAngle),   GI_MEMBER(T, blocking),
            GI_MEMBER(T, occlusionStrength), GI_MEMBER(T, cascadeCount), GI_MEMBER(T, intensity),  GI_MEMBER(T, damping),
            GI_MEMBER(T, cubeFace),      GI_MEMBER(T, skyIntensity),   GI_MEMBER(T, skyRotation),  GI_MEMBER(T, skyCascade),
            GI_MEMBER(T, skyMipCount),   GI_MEMBER(T, skySH),          GI_MEMBER(T, skyMipRoughness)};
}

std::vector<Member> volumeMembers() {
    using T = VolumeParams;
    return {GI_MEMBER(T, invViewProj), GI_MEMBER(T, eye),         GI_MEMBER(T, boxMin),      GI_MEMBER(T, boxMax),
            GI_MEMBER(T, sigmaS),      GI_MEMBER(T, sigmaT),      GI_MEMBER(T, fullWidth),   GI_MEMBER(T, fullHeight),
            GI_MEMBER(T, lowWidth),    GI_MEMBER(T, lowHeight),   GI_MEMBER(T, toFullX),     GI_MEMBER(T, toFullY),
            GI_MEMBER(T, samples),     GI_MEMBER(T, jitter),      GI_MEMBER(T, pcf),         GI_MEMBER(T, phase),
            GI_MEMBER(T, g),           GI_MEMBER(T, k),           GI_MEMBER(T, intensity),   GI_MEMBER(T, shadowSize),
            GI_MEMBER(T, lightFirst),  GI_MEMBER(T, lightCount),  GI_MEMBER(T, accumulate),  GI_MEMBER(T, depthAware),
            GI_MEMBER(T, attenuateScene), GI_MEMBER(T, pad0),     GI_MEMBER(T, pad1),        GI_MEMBER(T, pad2)};
}

std::vector<Member> renderMembers() {
    using T = RenderParams;
    return {GI_MEMBER(T, viewProj),    GI_MEMBER(T, invViewProj), GI_MEMBER(T, cameraPos),
            GI_MEMBER(T, lightPos),    GI_MEMBER(T, shadowFar),   GI_MEMBER(T, pad0),
            GI_MEMBER(T, shadowSize),  GI_MEMBER(T, pcfRadius),   GI_MEMBER(T, shadowBias),  GI_MEMBER(T, specular),
            GI_MEMBER(T, exposureScale), GI_MEMBER(T, toneOp),    GI_MEMBER(T, channelMask), GI_MEMBER(T, direction),
            GI_MEMBER(T, pan),         GI_MEMBER(T, zoom),        GI_MEMBER(T, level),       GI_MEMBER(T, mode),
            GI_MEMBER(T, axis),        GI_MEMBER(T, slice),       GI_MEMBER(T, shComponent), GI_MEMBER(T, depthNear),
            GI_MEMBER(T, depthFar),    GI_MEMBER(T, range),       GI_MEMBER(T, scale),       GI_MEMBER(T, falseColour),
            GI_MEMBER(T, depthCube),   GI_MEMBER(T, firstTriangle), GI_MEMBER(T, skipEmitter)};
}

std::vector<Member> vctMembers() {
    using T = vct::VCTParams;
    return {GI_MEMBER(T, gridMin),       GI_MEMBER(T, wrapOffset),   GI_MEMBER(T, clipMin),       GI_MEMBER(T, clipMax),
            GI_MEMBER(T, resolution),    GI_MEMBER(T, cellSize),     GI_MEMBER(T, lightFirst),    GI_MEMBER(T, lightCount),
            GI_MEMBER(T, accumulate),    GI_MEMBER(T, sides),        GI_MEMBER(T, sliceAxis),     GI_MEMBER(T, level0),
            GI_MEMBER(T, destSize),     GI_MEMBER(T, sourceLevel),
            GI_MEMBER(T, direction),     GI_MEMBER(T, sourceOffsetX), GI_MEMBER(T, destOffsetX),  GI_MEMBER(T, coneCount),
            GI_MEMBER(T, tanHalf),       GI_MEMBER(T, maxDistance),  GI_MEMBER(T, occlusionDistance), GI_MEMBER(T, levelCount),
            GI_MEMBER(T, maxLod),        GI_MEMBER(T, nudge),        GI_MEMBER(T, stepMultiplier), GI_MEMBER(T, cones),
            GI_MEMBER(T, levelMinCell),  GI_MEMBER(T, levelWrap),    GI_MEMBER(T, invViewProj),   GI_MEMBER(T, cameraPos),
            GI_MEMBER(T, imageSize),     GI_MEMBER(T, toFull),       GI_MEMBER(T, specularAperture), GI_MEMBER(T, vao),
            GI_MEMBER(T, vaoStrength),   GI_MEMBER(T, intensity),    GI_MEMBER(T, specularCone),  GI_MEMBER(T, nearPlane),
            GI_MEMBER(T, farPlane),      GI_MEMBER(T, exposureScale), GI_MEMBER(T, opacityThreshold), GI_MEMBER(T, viewSource),
            GI_MEMBER(T, viewMip),       GI_MEMBER(T, edges),        GI_MEMBER(T, sh),          GI_MEMBER(T, background),
            GI_MEMBER(T, sky),           GI_MEMBER(T, skyMipRoughness)};
}

// Where the driver's layout of `block` in `program` differs from the C++ struct's, one line per
// difference; empty when they agree. Members are named "<instance>.<member>" by GL.
std::vector<std::string> layoutDifferences(GLuint program, const char* block, const std::string& instance, size_t bytes,
                                           const std::vector<Member>& members) {
    std::vector<std::string> diffs;
    GLuint index = glGetProgramResourceIndex(program, GL_UNIFORM_BLOCK, block);
    if (index == GL_INVALID_INDEX) return {std::string("no block ") + block};
    const GLenum blockProps[2] = {GL_BUFFER_DATA_SIZE, GL_NUM_ACTIVE_VARIABLES};
    GLint blockValues[2] = {};
    glGetProgramResourceiv(program, GL_UNIFORM_BLOCK, index, 2, blockProps, 2, nullptr, blockValues);
    if (size_t(blockValues[0]) != bytes)
        diffs.push_back("block size " + std::to_string(blockValues[0]) + ", C++ " + std::to_string(bytes));
    std::vector<GLint> variables(static_cast<size_t>(blockValues[1]));
    const GLenum activeProp = GL_ACTIVE_VARIABLES;
    glGetProgramResourceiv(program, GL_UNIFORM_BLOCK, index, 1, &activeProp, GLsizei(variables.size()), nullptr, variables.data());

    struct Layout {
        GLint offset, arrayStride, matrixStride, rowMajor, type;
    };
    std::map<std::string, Layout> gl;
    for (GLint v : variables) {
        char name[256];
        glGetProgramResourceName(program, GL_UNIFORM, GLuint(v), sizeof(name), nullptr, name);
        const GLenum props[5] = {GL_OFFSET, GL_ARRAY_STRIDE, GL_MATRIX_STRIDE, GL_IS_ROW_MAJOR, GL_TYPE};
        GLint values[5] = {};
        glGetProgramResourceiv(program, GL_UNIFORM, GLuint(v), 5, props, 5, nullptr, values);
        gl[name] = {values[0], values[1], values[2], values[3], values[4]};
    }
    for (const Member& m : members) {
        std::string name = instance + "." + m.name;
        auto it = gl.find(name);
        if (it == gl.end()) {
            diffs.push_back(name + " not in the block");
            continue;
        }
        const Layout& l = it->second;
        if (size_t(l.offset) != m.offset)
            diffs.push_back(name + " at " + std::to_string(l.offset) + ", C++ " + std::to_string(m.offset));
        if (size_t(std::max(l.arrayStride, 0)) != m.arrayStride)
            diffs.push_back(name + " array stride " + std::to_string(l.arrayStride) + ", C++ " + std::to_string(m.arrayStride));
        // glm's mat4 is four vec4 columns.
        if (l.type == GL_FLOAT_MAT4 && (l.matrixStride != GLint(sizeof(glm::vec4)) || l.rowMajor))
            diffs.push_back(name + " is not column-major with vec4 columns");
        gl.erase(it);
    }
    for (const auto& [name, l] : gl) diffs.push_back(name + " at " + std::to_string(l.offset) + " has no C++ member");
    return diffs;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const std::string& l : lines) s += l + "\n";
    return s;
}

class ParamBlock : public test::GLTest {};

TEST_F(ParamBlock, SSAOLayoutMatchesTheDriver) {
    for (const auto& [name, frag] : {std::pair{"ssao", "ssao/ssao.frag"}, std::pair{"ssaoBlur", "ssao/ssao_blur.frag"}}) {
        gl::Program p = gl::fullscreenProgram(name, frag);
        std::vector<std::string> diffs = layoutDifferences(p.id(), kSSAOBlockName, "uSSAO", sizeof(SSAOParams), ssaoMembers());
        EXPECT_TRUE(diffs.empty()) << name << ":\n" << joined(diffs);
    }
}

TEST_F(ParamBlock, EnvironmentLayoutMatchesTheDriver) {
    for (const char* comp : {"to_cube", "prefilter", "brdf_lut", "shade", "sky"}) {
        gl::Program p(comp, {{GL_COMPUTE_SHADER, std::string("envmap/") + comp + ".comp"}});
        std::vector<std::string> diffs = layoutDifferences(p.id(), kEnvBlockName, "uEnv", sizeof(EnvParams), envMembers());
        EXPECT_TRUE(diffs.empty()) << comp << ":\n" << joined(diffs);
    }
}

TEST_F(ParamBlock, LPVLayoutMatchesTheDriver) {
    std::vector<std::pair<std::string, std::vector<gl::StageSource>>> programs = {
        {"rsm", {{GL_VERTEX_SHADER, "lpv/rsm.vert"}, {GL_FRAGMENT_SHADER, "lpv/rsm.frag"}}}};
    for (const char* comp : {"inject", "geometry", "geometry_resolve", "transmit", "propagate", "resolve", "shade"})
        programs.push_back({comp, {{GL_COMPUTE_SHADER, std::string("lpv/") + comp + ".comp"}}});
    for (const auto& [name, stages] : programs) {
        gl::Program p(name, stages);
        std::vector<std::string> diffs = layoutDifferences(p.id(), kLPVBlockName, "uLPV", sizeof(LPVParams), lpvMembers());
        EXPECT_TRUE(diffs.empty()) << name << ":\n" << joined(diffs);
    }
}

// Every raster program of the frame pipeline, as gi/render/renderer.cpp builds them.
TEST_F(ParamBlock, RenderLayoutMatchesTheDriver) {
    std::vector<std::pair<std::string, gl::Program>> programs;
    programs.emplace_back("gbuffer", gl::Program("gbuffer", {{GL_VERTEX_SHADER, "render/gbuffer.vert"},
                                                             {GL_FRAGMENT_SHADER, "render/gbuffer.frag"}}));
    for (const char* linear : {"LINEAR_DEPTH=0", "LINEAR_DEPTH=1"})
        programs.emplace_back(linear, gl::Program("shadow", {{GL_VERTEX_SHADER, "render/shadow.vert"},
                                                             {GL_FRAGMENT_SHADER, "render/shadow.frag"}}, {linear}));
    for (const char* frag : {"composite", "tonemap", "view"})
        programs.emplace_back(frag, gl::fullscreenProgram(frag, (std::string("render/") + frag + ".frag").c_str()));
    for (int kind = 0; kind < Renderer::kLightKinds; ++kind)
        programs.emplace_back("light kind " + std::to_string(kind), Renderer::lightPassProgram(kind));
    for (const auto& [name, p] : programs) {
        std::vector<std::string> diffs = layoutDifferences(p.id(), kRenderBlockName, "uRender", sizeof(RenderParams), renderMembers());
        EXPECT_TRUE(diffs.empty()) << name << ":\n" << joined(diffs);
    }
}

// The per-draw material block (common/material_shared.h) in every program that draws the
// scene's materials: G-buffer, both shadow variants, LPV's RSM and VCT's voxelization.
TEST_F(ParamBlock, MaterialLayoutMatchesTheDriver) {
    using T = MaterialParams;
    std::vector<Member> members = {GI_MEMBER(T, baseColor),   GI_MEMBER(T, emissive),   GI_MEMBER(T, uvTransform),
                                   GI_MEMBER(T, alphaCutoff), GI_MEMBER(T, alphaMode),  GI_MEMBER(T, roughness),
                                   GI_MEMBER(T, metallic),    GI_MEMBER(T, normalScale), GI_MEMBER(T, occlusionStrength),
                                   GI_MEMBER(T, textureMask), GI_MEMBER(T, doubleSided)};
    std::vector<std::pair<std::string, gl::Program>> programs;
    programs.emplace_back("gbuffer", gl::Program("gbuffer", {{GL_VERTEX_SHADER, "render/gbuffer.vert"},
                                                             {GL_FRAGMENT_SHADER, "render/gbuffer.frag"}}));
    for (const char* linear : {"LINEAR_DEPTH=0", "LINEAR_DEPTH=1"})
        programs.emplace_back(linear, gl::Program("shadow", {{GL_VERTEX_SHADER, "render/shadow.vert"},
                                                             {GL_FRAGMENT_SHADER, "render/shadow.frag"}}, {linear}));
    programs.emplace_back("rsm", gl::Program("rsm", {{GL_VERTEX_SHADER, "lpv/rsm.vert"}, {GL_FRAGMENT_SHADER, "lpv/rsm.frag"}}));
    programs.emplace_back("voxelize", gl::Program("voxelize", {{GL_VERTEX_SHADER, "vct/voxelize.vert"},
                                                               {GL_GEOMETRY_SHADER, "vct/voxelize.geom"},
                                                               {GL_FRAGMENT_SHADER, "vct/voxelize.frag"}}));
    for (const auto& [name, p] : programs) {
        std::vector<std::string> diffs = layoutDifferences(p.id(), kMaterialBlockName, "uMaterialParams", sizeof(T), members);
        EXPECT_TRUE(diffs.empty()) << name << ":\n" << joined(diffs);
    }
}

TEST_F(ParamBlock, VolumetricLayoutMatchesTheDriver) {
    for (const char* comp : {"march", "blur", "composite"}) {
        gl::Program p(comp, {{GL_COMPUTE_SHADER, std::string("volumetric/") + comp + ".comp"}});
        std::vector<std::string> diffs = layoutDifferences(p.id(), kVolumeBlockName, "uVolume", sizeof(VolumeParams), volumeMembers());
        EXPECT_TRUE(diffs.empty()) << comp << ":\n" << joined(diffs);
    }
}

// Every VCT program, and the bounce and trace programs in each variant the host compiles (the
// level count, anisotropic and SH voxels), lay the block out as C++ does.
TEST_F(ParamBlock, VCTLayoutMatchesTheDriver) {
    auto check = [](const gl::Program& p, const std::string& what) {
        std::vector<std::string> diffs = layoutDifferences(p.id(), vct::kVCTBlockName, "uVCT", sizeof(vct::VCTParams), vctMembers());
        EXPECT_TRUE(diffs.empty()) << what << ":\n" << joined(diffs);
    };
    check(gl::Program("voxelize", {{GL_VERTEX_SHADER, "vct/voxelize.vert"},
                                   {GL_GEOMETRY_SHADER, "vct/voxelize.geom"},
                                   {GL_FRAGMENT_SHADER, "vct/voxelize.frag"}}),
          "voxelize");
    check(gl::fullscreenProgram("voxelView", "vct/voxel_view.frag"), "voxelView");
    for (const char* comp : {"clear", "inject", "resolve", "mip", "upsample", "compact"})
        check(gl::Program(comp, {{GL_COMPUTE_SHADER, std::string("vct/") + comp + ".comp"}}), comp);
    struct Variant {
        int levels, aniso, sh;
    };
    for (Variant v : {Variant{1, 0, 0}, Variant{1, 1, 0}, Variant{1, 0, 1}, Variant{3, 0, 0}, Variant{vct::kVCTMaxLevels, 0, 0}})
        for (const char* comp : {"bounce", "trace"}) {
            std::vector<std::string> defines = {"VCT_LEVELS " + std::to_string(v.levels), "VCT_ANISO " + std::to_string(v.aniso),
                                                "VCT_SH " + std::to_string(v.sh)};
            std::string what = std::string(comp) + " levels " + defines[0] + ", " + defines[1] + ", " + defines[2];
            check(gl::Program(comp, {{GL_COMPUTE_SHADER, std::string("vct/") + comp + ".comp"}}, defines), what);
        }
}

// A copy of the shader tree to edit, made the shader root for the test's lifetime.
class ParamBlockShaders : public test::GLTest {
protected:
    std::filesystem::path mDir;
    void SetUp() override {
        test::GLTest::SetUp();
        mDir = test::tempDir() / "shaders";
        std::filesystem::copy(GI_SHADER_DIR, mDir, std::filesystem::copy_options::recursive);
        setenv("GI_SHADER_DIR", mDir.c_str(), 1);
    }
    void TearDown() override {
        unsetenv("GI_SHADER_DIR");
        test::GLTest::TearDown();
    }
    // Replaces `from` (which must occur) by `to` in the copy of `file`.
    void edit(const std::string& file, const std::string& from, const std::string& to) {
        std::ifstream in(mDir / file);
        std::stringstream text;
        text << in.rdbuf();
        std::string s = text.str();
        size_t at = s.find(from);
        ASSERT_NE(at, std::string::npos) << from << " not in " << file;
        s.replace(at, from.size(), to);
        std::ofstream(mDir / file) << s;
    }
    template <class Make>
    std::string errorOf(Make&& make) {
        try {
            make();
        } catch (const Error& e) {
            return e.what();
        }
        return "no error";
    }
};

// The comparison above can fail: a vec3 where C++ has three floats moves every later member in
// GLSL (std140 aligns a vec3 to 16 bytes), and the block grows.
TEST_F(ParamBlockShaders, LayoutThatDiffersFromCppIsCaught) {
    edit("ssao/ssao_shared.h", "    float pad0;\n    float pad1;\n    float pad2;\n", "    vec3 pad0;\n");
    gl::Program p = gl::fullscreenProgram("ssao", "ssao/ssao.frag");
    std::string diffs = joined(layoutDifferences(p.id(), kSSAOBlockName, "uSSAO", sizeof(SSAOParams), ssaoMembers()));
    EXPECT_NE(diffs.find("block size 1520, C++ 1504"), std::string::npos) << diffs;
    EXPECT_NE(diffs.find("uSSAO.view at 48, C++ 32"), std::string::npos) << diffs;
    EXPECT_NE(diffs.find("uSSAO.pad1 not in the block"), std::string::npos) << diffs;
    // The pass refuses it at construction, naming the shader and the block.
    std::string msg = errorOf([] { SSAO ssao; });
    EXPECT_NE(msg.find("shader ssao: uniform block SSAOBlock holds 1520 bytes"), std::string::npos) << msg;
}

TEST_F(ParamBlockShaders, BlockAtAnotherBindingIsAnErrorNamingTheShader) {
    edit("envmap/envmap_shared.h", "binding = kEnvBlockBinding", "binding = 3");
    std::string msg = errorOf([] { Environment env; });
    EXPECT_NE(msg.find("shader environment.toCube: uniform block EnvBlock is at binding 3, the host binds it at 0"), std::string::npos)
        << msg;
}

TEST_F(ParamBlockShaders, LPVAndVolumetricRefuseABlockAtAnotherBinding) {
    edit("lpv/lpv_shared.h", "binding = kLPVBlockBinding", "binding = 3");
    std::string msg = errorOf([] { LPV lpv; });
    EXPECT_NE(msg.find("shader lpv.rsm: uniform block LPVBlock is at binding 3, the host binds it at 0"), std::string::npos) << msg;
    edit("volumetric/volumetric_shared.h", "binding = kVolumeBlockBinding", "binding = 3");
    msg = errorOf([] { Volumetric volumetric; });
    EXPECT_NE(msg.find("shader volumetric.march: uniform block VolumeBlock is at binding 3, the host binds it at 0"),
              std::string::npos)
        << msg;
}

TEST_F(ParamBlockShaders, RenderBlockAtAnotherBindingIsAnErrorNamingTheShader) {
    edit("render/render_shared.h", "binding = kRenderBlockBinding", "binding = 2");
    std::string msg = errorOf([] { Renderer renderer; });
    EXPECT_NE(msg.find("shader gbuffer: uniform block RenderBlock is at binding 2, the host binds it at 0"), std::string::npos)
        << msg;
}

TEST_F(ParamBlockShaders, MisspeltOrMissingBlockIsAnErrorNamingTheShader) {
    edit("ssao/ssao_shared.h", "uniform SSAOBlock", "uniform SSAOBlok");
    std::string msg = errorOf([] { SSAO ssao; });
    EXPECT_NE(msg.find("shader ssao: uniform block SSAOBlock is not declared in common/fullscreen.vert, ssao/ssao.frag"),
              std::string::npos)
        << msg;
    // A program that never includes the header.
    std::ofstream(mDir / "plain.comp") << "layout(local_size_x = 1) in;\nvoid main() {}\n";
    gl::Program plain("plain", {{GL_COMPUTE_SHADER, "plain.comp"}});
    gl::UniformBlock<EnvParams> block(kEnvBlockName, kEnvBlockBinding);
    msg = errorOf([&] { block.requireIn(plain); });
    EXPECT_NE(msg.find("shader plain: uniform block EnvBlock is not declared in plain.comp"), std::string::npos) << msg;
}

// A reload checks the blocks again: a bad one keeps the last good program and says why.
TEST_F(ParamBlockShaders, ReloadRechecksTheBlock) {
    SSAO ssao;
    edit("ssao/ssao_shared.h", "binding = kSSAOBlockBinding", "binding = 2");
    std::string log;
    EXPECT_FALSE(ssao.reloadShaders(log));
    EXPECT_NE(log.find("shader ssaoBlur: uniform block SSAOBlock is at binding 2"), std::string::npos) << log;
    edit("ssao/ssao_shared.h", "binding = 2", "binding = kSSAOBlockBinding");
    log.clear();
    EXPECT_TRUE(ssao.reloadShaders(log)) << log;
}

// The bounce and trace programs, built when the voxel layout changes, check the block too: at
// the recompile and at a reload.
TEST_F(ParamBlockShaders, VCTProgramsCheckTheBlockAtRecompileAndReload) {
    Scene scene = makeBuiltinScene("cornell");
    Preset preset;
    preset.header.technique.name = "vct";
    preset.vct.gridResolution = 16;
    preset.vct.bounceCount = 2;
    FrameSettings fs = frameSettings(preset, scene, 32, 24);
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    edit("vct/vct_shared.h", "binding = kVCTBlockBinding", "binding = 3");
    std::string log;
    EXPECT_FALSE(r.reloadShaders(log));
    EXPECT_NE(log.find("shader vct.voxelize: uniform block VCTBlock is at binding 3, the host binds it at 0"), std::string::npos) << log;
    EXPECT_NE(log.find("shader vct.trace: uniform block VCTBlock is at binding 3"), std::string::npos) << log;
    fs.vct.sh = true;  // recompiles bounce and trace
    std::string msg = errorOf([&] { r.render(fs); });
    EXPECT_NE(msg.find("shader vct.bounce: uniform block VCTBlock is at binding 3"), std::string::npos) << msg;
}

}  // namespace
}  // namespace gi
