// A technique's shader parameters as one std140 struct in a uniform buffer. The struct, its
// block and the block's binding are written once in shaders/<technique>/<technique>_shared.h,
// which C++ and GLSL both include (shaders/ssao/ssao_shared.h is the pattern): a misspelt field
// fails to compile in either language, and Program::requireBlock turns a block the shader names
// or binds differently into an error at link, where a uniform name looked up by string gave -1.
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"

#include <string>
#include <type_traits>
#include <utility>

namespace gi::gl {

template <class T>
class UniformBlock {
    static_assert(std::is_trivially_copyable_v<T>, "a uniform block is uploaded byte for byte");
    static_assert(sizeof(T) % 16 == 0, "std140 rounds a struct up to 16 bytes: pad the C++ struct alike");

public:
    // `block` is the GLSL block's name, `binding` its binding constant from the shared header.
    UniformBlock(std::string block, GLuint binding)
        : mName(std::move(block)), mBinding(binding), mBuffer(createBuffer(sizeof(T), nullptr, GL_DYNAMIC_STORAGE_BIT)) {}

    // Makes `program` check now and at every reload that it declares this block at this binding
    // with sizeof(T) bytes; throws gi::Error naming the shader and the block.
    void requireIn(Program& program) const { program.requireBlock(mName, mBinding, sizeof(T)); }

    // Uploads `params` and binds the buffer at the block's binding for the draws and dispatches
    // that follow. GL orders the upload after earlier commands that read the buffer. Since each
    // pass binds its block before it runs, techniques may use the same binding numbers.
    void set(const T& params) const {
        glNamedBufferSubData(mBuffer.id(), 0, GLsizeiptr(sizeof(T)), &params);
        glBindBufferBase(GL_UNIFORM_BUFFER, mBinding, mBuffer.id());
    }

private:
    std::string mName;
    GLuint mBinding = 0;
    Buffer mBuffer;
};

}  // namespace gi::gl
