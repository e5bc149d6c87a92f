// Shared by the LPV compute passes: cell indexing and float addition on uint storage.
#include "lpv/lpv_shared.h"
#include "common/sh.h"

// The six axis directions, in the order of the transmittance buffer (transmit.comp): +x -x +y -y +z -z.
const ivec3 kDirections[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0), ivec3(0, 0, 1), ivec3(0, 0, -1));

int cellIndex(ivec3 c, int res) { return (c.z * res + c.y) * res + c.x; }
bool insideGrid(ivec3 c, int res) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(res))); }
int cellIndex(ivec3 c) { return cellIndex(c, uLPV.resolution); }
bool insideGrid(ivec3 c) { return insideGrid(c, uLPV.resolution); }
