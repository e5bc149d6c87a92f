// Constants of the SSAO pass shared by C++ (gi/ssao/ssao.cpp) and GLSL (shaders/ssao/). The
// passes read the G-buffer on the lighting pass's units (kUnitDepth, kUnitNormal) and the blur
// reads the raw AO on kUnitSource, all from common/shared.h.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

// Size of the kernel uniform array: SSAOSettings::sampleCount is at most this.
GI_CONST int kSSAOMaxSamples = 64;
// Side of the tiled rotation-noise pattern; a box blur 2 * 2 pixels wide covers one tile.
GI_CONST int kSSAONoiseSize = 4;

#ifdef __cplusplus
}  // namespace gi::shared
#endif
