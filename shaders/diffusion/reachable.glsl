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

// Whether light can reach occupied cell c from the side that a surface of normal n faces: an
// empty face neighbour inside the grid in a direction with a positive component along n. The
// cell where a room's floor meets a wall is open only below the floor, to the outside (or, under
// a shared wall, to the room next door): it is reachable, but from behind the surface, and the
// little light it holds drew a dark line along every edge of a closed room (and the light of the
// next room along the foot of a shared wall).
bool reachableFrom(ivec3 c, vec3 n) {
    for (int d = 0; d < 6; ++d) {
        ivec3 m = c + kDirections[d];
        if (dot(vec3(kDirections[d]), n) > 0.0 && insideGrid(m) && !occupied(imageLoad(uAlbedo, m).r)) return true;
    }
    return false;
}
