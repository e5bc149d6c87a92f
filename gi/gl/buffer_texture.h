// Buffer textures (gl::createBufferTexture in handle.h): views of a buffer's storage that
// compute passes read with texelFetch and write as an imageBuffer. On llvmpipe they are the fast
// path for grids addressed per invocation (lpv/propagate.comp says why).
#pragma once

#include <cstddef>
#include <string>

namespace gi::gl {

// Throws a gi::Error naming `setting` when a view of `texels` texels exceeds this GL's
// GL_MAX_TEXTURE_BUFFER_SIZE (the spec's minimum is 65536; llvmpipe allows 2^27).
void requireBufferTexels(size_t texels, const std::string& setting);

}  // namespace gi::gl
