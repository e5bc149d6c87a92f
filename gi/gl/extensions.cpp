#include "gi/gl/extensions.h"

#include <epoxy/gl.h>

#include <cstdlib>
#include <sstream>

namespace gi::gl {

bool hasExtension(const std::string& name) {
    if (const char* off = std::getenv("GI_DISABLE_GL_EXTENSIONS")) {
        std::istringstream list(off);
        for (std::string item; std::getline(list, item, ',');)
            if (item == name) return false;
    }
    return epoxy_has_gl_extension(name.c_str());
}

std::string floatAtomicsDefine() {
    return std::string("FLOAT_ATOMICS=") + (hasExtension("GL_NV_shader_atomic_float") ? "1" : "0");
}

}  // namespace gi::gl
