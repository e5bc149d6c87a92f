// Shared by the LPV compute passes: cell indexing and float addition on uint storage.
#include "lpv/lpv_shared.h"
#include "common/sh.h"

int cellIndex(ivec3 c) { return (c.z * uLPV.resolution + c.y) * uLPV.resolution + c.x; }
bool insideGrid(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(uLPV.resolution))); }
