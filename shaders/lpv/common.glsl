// Shared by the LPV compute passes: cell indexing and float addition on uint storage.
#include "common/shared.h"
#include "common/sh.h"

uniform int uResolution;

int cellIndex(ivec3 c) { return (c.z * uResolution + c.y) * uResolution + c.x; }
bool insideGrid(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(uResolution))); }
