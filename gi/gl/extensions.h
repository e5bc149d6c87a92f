// Optional GL extensions the passes use when the driver has them, with a way to test the
// fallback on a driver that does.
#pragma once

#include <string>

namespace gi::gl {

// Whether the current context offers extension `name` (libepoxy's query), unless `name` is
// listed in the environment variable GI_DISABLE_GL_EXTENSIONS (comma-separated): tests and users
// force the code path a driver without it takes.
bool hasExtension(const std::string& name);

// "FLOAT_ATOMICS=1" where GL_NV_shader_atomic_float gives atomicAdd on floats in shader storage
// (Mesa llvmpipe, NVIDIA), else "FLOAT_ATOMICS=0": the define common/atomic_float.glsl reads,
// for passes that add floats from many invocations into one cell (LPV's injection and geometry
// volume), which otherwise loop on atomicCompSwap.
std::string floatAtomicsDefine();

}  // namespace gi::gl
