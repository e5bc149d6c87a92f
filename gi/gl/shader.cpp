#include "gi/gl/shader.h"

#include "common/shared.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"

#include <regex>
#include <set>
#include <sstream>

namespace gi::gl {

void dispatch3D(glm::ivec3 n) {
    glDispatchCompute(groupCount(n.x, shared::kGroup3DX), groupCount(n.y, shared::kGroup3DY), groupCount(n.z, shared::kGroup3DZ));
}

namespace {

constexpr int kMaxIncludeDepth = 16;

void expand(const std::string& file, std::vector<std::string>& files, std::set<std::string>& included,
            std::ostringstream& out, int depth) {
    if (depth > kMaxIncludeDepth) throw Error("shader " + file + ": includes nested deeper than 16 (a cycle?)");
    if (!included.insert(file).second) return;  // every file is included once per stage
    int index = int(files.size());
    files.push_back(file);
    std::string text;
    try {
        text = readTextFile(shaderDir() / file);
    } catch (const Error&) {
        throw Error("shader " + file + ": cannot read " + (shaderDir() / file).string());
    }
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    out << "#line 1 " << index << "\n";
    static const std::regex includeRe(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
    static const std::regex onceRe(R"(^\s*#\s*pragma\s+once\s*$)");
    while (std::getline(in, line)) {
        ++lineNo;
        std::smatch m;
        if (std::regex_match(line, m, includeRe)) {
            expand(m[1].str(), files, included, out, depth + 1);
            out << "#line " << lineNo + 1 << " " << index << "\n";
        } else if (std::regex_match(line, onceRe)) {
            out << "\n";
        } else {
            out << line << "\n";
        }
    }
}

// Rewrites "N:LINE(COL)" (Mesa) or "N(LINE)" (NVIDIA) prefixes into "file:LINE".
std::string mapLog(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex mesaRe(R"(^(\d+):(\d+)\((\d+)\):?\s*(.*)$)");
    static const std::regex nvRe(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
    std::istringstream in(log);
    std::string line, out;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_match(line, m, mesaRe) || std::regex_match(line, m, nvRe)) {
            size_t f = std::stoul(m[1].str());
            std::string name = f < files.size() ? files[f] : "?";
            std::string rest = m[m.size() - 1].str();
            out += name + ":" + m[2].str() + ": " + rest + "\n";
        } else if (!line.empty()) {
            out += line + "\n";
        }
    }
    return out;
}

std::string firstLine(const std::string& s) {
    auto nl = s.find('\n');
    return nl == std::string::npos ? s : s.substr(0, nl);
}

}  // namespace

std::string preprocessShader(const std::string& file, const std::vector<std::string>& defines,
                             std::vector<std::string>& files) {
    std::ostringstream out;
    out << "#version 450 core\n";
    for (const auto& d : defines) {
        auto eq = d.find('=');
        if (eq == std::string::npos) out << "#define " << d << "\n";
        else out << "#define " << d.substr(0, eq) << " " << d.substr(eq + 1) << "\n";
    }
    std::set<std::string> included;
    expand(file, files, included, out, 0);
    return out.str();
}

Program::Program(std::string name, std::vector<StageSource> stages, std::vector<std::string> defines)
    : mName(std::move(name)), mStages(std::move(stages)), mDefines(std::move(defines)) {
    mProgram = build();
}

ProgramHandle Program::build() const {
    ProgramHandle program(glCreateProgram());
    std::vector<ShaderHandle> shaders;
    for (const auto& s : mStages) {
        std::vector<std::string> files;
        std::string src = preprocessShader(s.file, mDefines, files);
        ShaderHandle sh(glCreateShader(s.stage));
        const char* p = src.c_str();
        glShaderSource(sh.id(), 1, &p, nullptr);
        glCompileShader(sh.id());
        GLint ok = 0;
        glGetShaderiv(sh.id(), GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint len = 0;
            glGetShaderiv(sh.id(), GL_INFO_LOG_LENGTH, &len);
            std::string log(size_t(std::max(len, 1)), '\0');
            glGetShaderInfoLog(sh.id(), len, nullptr, log.data());
            std::string mapped = mapLog(log.c_str(), files);
            throw Error("shader " + mName + ": compile failed: " + firstLine(mapped) +
                        (mapped.find('\n') + 1 < mapped.size() ? " (more in the log)" : ""));
        }
        glAttachShader(program.id(), sh.id());
        shaders.push_back(std::move(sh));
    }
    glLinkProgram(program.id());
    GLint ok = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetProgramInfoLog(program.id(), len, nullptr, log.data());
        throw Error("shader " + mName + ": link failed: " + firstLine(log.c_str()));
    }
    for (auto& sh : shaders) glDetachShader(program.id(), sh.id());
    for (const BlockRequirement& b : mBlocks) checkBlock(program.id(), b);
    return program;
}

void Program::requireBlock(std::string block, GLuint binding, size_t bytes) {
    BlockRequirement b{std::move(block), binding, bytes};
    checkBlock(mProgram.id(), b);
    mBlocks.push_back(std::move(b));
}

void Program::checkBlock(GLuint program, const BlockRequirement& b) const {
    std::string files;
    for (const StageSource& s : mStages) files += (files.empty() ? "" : ", ") + s.file;
    const std::string where = "shader " + mName + ": uniform block " + b.name;
    GLuint index = glGetProgramResourceIndex(program, GL_UNIFORM_BLOCK, b.name.c_str());
    if (index == GL_INVALID_INDEX) throw Error(where + " is not declared in " + files + " (is its header included?)");
    const GLenum props[2] = {GL_BUFFER_BINDING, GL_BUFFER_DATA_SIZE};
    GLint values[2] = {};
    glGetProgramResourceiv(program, GL_UNIFORM_BLOCK, index, 2, props, 2, nullptr, values);
    if (GLuint(values[0]) != b.binding)
        throw Error(where + " is at binding " + std::to_string(values[0]) + ", the host binds it at " + std::to_string(b.binding));
    if (size_t(values[1]) != b.bytes)
        throw Error(where + " holds " + std::to_string(values[1]) + " bytes, the host's struct " + std::to_string(b.bytes) +
                    " (a member the two languages lay out differently?)");
}

Program fullscreenProgram(const char* name, const char* frag, std::vector<std::string> defines) {
    return Program(name, {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, frag}}, std::move(defines));
}

bool Program::reload() {
    try {
        ProgramHandle fresh = build();
        mProgram = std::move(fresh);
        mLocations.clear();
        mLog.clear();
        return true;
    } catch (const Error& e) {
        mLog = e.what();
        return false;
    }
}

GLint Program::location(const char* uniform) const {
    auto it = mLocations.find(uniform);
    if (it != mLocations.end()) return it->second;
    GLint loc = glGetUniformLocation(mProgram.id(), uniform);
    mLocations.emplace(uniform, loc);
    return loc;
}

}  // namespace gi::gl
