// The scene's mean free path (gi/scene/free_path.h) and the LPV grid fitted to it (gi/lpv/lpv.h,
// "Fitted grid"). No GL: these run on the scene alone.
#include "gi/lpv/lpv.h"
#include "gi/scene/free_path.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace gi;

// Inside a convex body lit uniformly from its walls, cosine-distributed rays leaving the walls
// cross it by 4 V / S on average (Cauchy's mean chord). The 4 x 3 x 4 m room: V = 48, S = 80, so
// 2.4 m. The occupancy grid stops a ray where it enters a wall's cell, up to one cell (6.4 cm)
// before the wall, so the measure may read a few per cent short, never long.
TEST(FreePath, AClosedRoomsMeanChordIsCauchys) {
    Scene room = test::closedRoom();
    FreePath p = meanFreePath(room);
    const double cauchy = 4.0 * 48.0 / 80.0;
    std::printf("closed room: %d rays, %.3f met a surface, mean %.3f m (Cauchy %.3f), cube %.3f m\n", p.rays,
                p.hitFraction, p.meanHitDistance, cauchy, p.cubeSize);
    EXPECT_EQ(p.rays, kFreePathRays);
    EXPECT_GT(p.hitFraction, 0.99f) << "a closed room lets no ray out";
    EXPECT_LT(p.meanHitDistance, cauchy);
    EXPECT_NEAR(p.meanHitDistance / cauchy, 1.0, 0.05);
    EXPECT_NEAR(p.meanDistance, p.meanHitDistance, 0.05 * cauchy);
}

// A lone floor: every ray leaves the cube, so nothing is met and the fit keeps the given grid.
TEST(FreePath, AnOpenFloorMeetsNothing) {
    Scene floor = test::openFloor();
    FreePath p = meanFreePath(floor);
    EXPECT_EQ(p.rays, kFreePathRays);
    EXPECT_EQ(p.hitFraction, 0.0f);
    EXPECT_EQ(p.meanHitDistance, 0.0f);
    EXPECT_GT(p.meanDistance, 0.0f);
    LPVSettings s;
    EXPECT_EQ(lpvGridResolution(s, p), s.gridResolution);
}

// The same room at any scale has the same free path in units of its size, so the same grid.
TEST(FreePath, TheFitIsTheSameAtAnyScale) {
    LPVSettings s;
    FreePath unit = meanFreePath(test::closedRoom());
    for (float scale : {0.01f, 100.0f}) {
        Scene scaled = test::closedRoom();
        for (Vertex& v : scaled.vertices) v.position *= scale;
        scaled.finalize();
        FreePath p = meanFreePath(scaled);
        EXPECT_NEAR(p.meanHitDistance / (scale * unit.meanHitDistance), 1.0, 1e-3) << scale;
        EXPECT_EQ(lpvGridResolution(s, p), lpvGridResolution(s, unit)) << scale;
    }
}

// The fit: a small closed room takes the coarsest grid, the two-room scene (twice as long, its
// rooms' gap spanning fewer cells) the next step, and settings that ask for a given grid get it.
TEST(FreePath, LPVFitsItsGridToTheFreePath) {
    LPVSettings s;
    FreePath room = meanFreePath(test::closedRoom()), rooms = meanFreePath(test::twoRooms());
    EXPECT_EQ(lpvGridResolution(s, room), kLPVFitMinCells);
    EXPECT_EQ(lpvGridResolution(s, rooms), kLPVFitMinCells + kLPVFitStep);
    // The rule: the coarsest grid, in steps of kLPVFitStep, on which the mean gap spans
    // kLPVFitCellsPerGap cells.
    FreePath path = room;
    path.meanHitDistance = path.cubeSize * kLPVFitCellsPerGap / 16.5f;  // 16.5 cells wanted
    EXPECT_EQ(lpvGridResolution(s, path), 24);
    path.meanHitDistance = path.cubeSize * kLPVFitCellsPerGap / 24.0f;  // exactly 24
    EXPECT_EQ(lpvGridResolution(s, path), 24);
    path.meanHitDistance = path.cubeSize / 20.0f;  // 120 cells wanted, 32 the finest allowed
    EXPECT_EQ(lpvGridResolution(s, path), s.gridResolution);
    // Never finer than asked: a 16^3 grid stays 16^3, a 20^3 one may be 16^3 or 20^3.
    LPVSettings coarse = s;
    coarse.gridResolution = 16;
    EXPECT_EQ(lpvGridResolution(coarse, room), 16);
    coarse.gridResolution = 20;
    path.meanHitDistance = path.cubeSize * kLPVFitCellsPerGap / 18.0f;
    EXPECT_EQ(lpvGridResolution(coarse, path), 20);
    EXPECT_EQ(lpvGridResolution(coarse, room), 16);
    // Off, or with cascades or a set extent, the grid is the one asked for.
    LPVSettings off = s, cascades = s, extent = s;
    off.fitGrid = false;
    cascades.cascadeCount = 2;
    extent.cascadeExtent = 5.0f;
    for (const LPVSettings* t : {&off, &cascades, &extent}) EXPECT_EQ(lpvGridResolution(*t, room), s.gridResolution);
}

// Work is bounded whatever the file holds: 4000 more floor triangles, each half the floor, would
// mark 130 million points half a cell apart; the budget spreads them, and the room still reads
// as closed (most rays now leave the floor, so the mean is the floor's, not the room's).
TEST(FreePath, ManyLargeTrianglesStayWithinThePointBudget) {
    Scene room = test::closedRoom();
    FreePath plain = meanFreePath(room);
    std::printf("closed room: %zu points\n", plain.points);
    EXPECT_LT(plain.points, kFreePathPointBudget);
    const std::vector<uint32_t> floor(room.indices.begin(), room.indices.begin() + 6);  // the floor quad's two triangles
    for (int copy = 0; copy < 2000; ++copy) room.indices.insert(room.indices.end(), floor.begin(), floor.end());
    room.draws.back().indexCount += 2000 * 6;
    room.finalize();
    FreePath crowded = meanFreePath(room);
    std::printf("with 4000 more floor triangles: %zu points, mean %.3f m (%.3f alone)\n", crowded.points, crowded.meanHitDistance,
                plain.meanHitDistance);
    const size_t largestTriangle = size_t(4 * kFreePathGrid + 1) * size_t(4 * kFreePathGrid + 2) / 2;  // its points
    EXPECT_LE(crowded.points, kFreePathPointBudget + largestTriangle) << "the budget, and the triangle that crossed it";
    EXPECT_GT(crowded.hitFraction, 0.99f) << "the spread points left holes in the walls";
}
