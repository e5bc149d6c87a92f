#include "gi/gl/buffer_texture.h"

#include "gi/util/error.h"

#include <epoxy/gl.h>

namespace gi::gl {

void requireBufferTexels(size_t texels, const std::string& setting) {
    GLint max = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max);
    if (double(texels) > double(max))
        throw Error(setting + ": the grid needs a buffer texture of " + std::to_string(texels) + " texels; this GL allows " +
                    std::to_string(max));
}

}  // namespace gi::gl
