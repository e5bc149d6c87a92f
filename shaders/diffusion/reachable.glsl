// Whether light can reach occupied cell c: it has an empty face neighbour inside the grid. A cell
// without one (where two walls meet, inside thick geometry) never holds light. Needs uAlbedo
// (the occupancy, kDiffusionImageAlbedo) declared before it is included.
bool reachable(ivec3 c) {
    for (int d = 0; d < 6; ++d) {
        ivec3 n = c + kDirections[d];
        if (insideGrid(n) && !occupied(imageLoad(uAlbedo, n).r)) return true;
    }
    return false;
}
