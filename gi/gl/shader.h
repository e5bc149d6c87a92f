// GLSL programs built from files under shaders/ with #include, host-injected defines and file
// names in compile errors. A failed reload keeps the last good program and its log.
#pragma once

#include "gi/gl/handle.h"

#include <glm/glm.hpp>

#include <map>
#include <string>
#include <vector>

namespace gi::gl {

// Workgroups covering n items in groups of `size` (shared::kGroup2D, kGroup1D).
inline GLuint groupCount(int n, int size) { return GLuint((n + size - 1) / size); }
// Dispatches a volume pass over a grid of n cells a side (n.x by n.y by n.z), in the volume
// passes' workgroups (shared::kGroup3DX by kGroup3DY by kGroup3DZ, common/shared.h).
void dispatch3D(glm::ivec3 n);
inline void dispatch3D(int n) { dispatch3D(glm::ivec3(n)); }

struct StageSource {
    GLenum stage;      // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER, ...
    std::string file;  // path relative to the shader root, e.g. "render/light.frag"
};

// Expands #include "file" (relative to the shader root) with #line markers. `files` receives the
// file of each source-string number used in #line, for mapping compile errors back to names.
std::string preprocessShader(const std::string& file, const std::vector<std::string>& defines,
                             std::vector<std::string>& files);

class Program;
// A program drawing one screen-covering triangle (common/fullscreen.vert) with fragment shader `frag`.
Program fullscreenProgram(const char* name, const char* frag, std::vector<std::string> defines = {});

class Program {
public:
    Program() = default;
    // Builds the program; throws gi::Error with file:line on compile or link failure.
    Program(std::string name, std::vector<StageSource> stages, std::vector<std::string> defines = {});

    // Rebuilds from disk. On failure keeps the previous program and returns false; log() says why.
    bool reload();
    const std::string& log() const { return mLog; }
    const std::string& name() const { return mName; }

    GLuint id() const { return mProgram.id(); }
    void use() const { glUseProgram(mProgram.id()); }
    GLint location(const char* uniform) const;

    void set(const char* n, int v) const { glProgramUniform1i(id(), location(n), v); }
    void set(const char* n, float v) const { glProgramUniform1f(id(), location(n), v); }
    void set(const char* n, const glm::vec2& v) const { glProgramUniform2fv(id(), location(n), 1, &v[0]); }
    void set(const char* n, const glm::vec3& v) const { glProgramUniform3fv(id(), location(n), 1, &v[0]); }
    void set(const char* n, const glm::vec4& v) const { glProgramUniform4fv(id(), location(n), 1, &v[0]); }
    void set(const char* n, const glm::ivec2& v) const { glProgramUniform2iv(id(), location(n), 1, &v[0]); }
    void set(const char* n, const glm::ivec3& v) const { glProgramUniform3iv(id(), location(n), 1, &v[0]); }
    void set(const char* n, const glm::mat4& v) const { glProgramUniformMatrix4fv(id(), location(n), 1, GL_FALSE, &v[0][0]); }

    // Requires the uniform block `block` at `binding` with `bytes` of data (gl::UniformBlock's
    // struct), now and at every reload: throws gi::Error naming the shader and the block when it
    // is missing or differs, where a stray name or binding would otherwise read zeros silently.
    void requireBlock(std::string block, GLuint binding, size_t bytes);

private:
    struct BlockRequirement {
        std::string name;
        GLuint binding;
        size_t bytes;
    };

    std::string mName;
    std::vector<StageSource> mStages;
    std::vector<std::string> mDefines;
    std::vector<BlockRequirement> mBlocks;
    ProgramHandle mProgram;
    std::string mLog;
    mutable std::map<std::string, GLint, std::less<>> mLocations;

    ProgramHandle build() const;  // throws gi::Error
    void checkBlock(GLuint program, const BlockRequirement& b) const;  // throws gi::Error
};

}  // namespace gi::gl
