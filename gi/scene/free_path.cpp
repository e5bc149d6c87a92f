#include "gi/scene/free_path.h"

#include "gi/util/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace gi {

namespace {

struct Grid {
    glm::vec3 min{0.0f};
    float cell = 0.0f;
    int n = kFreePathGrid;
    std::vector<uint8_t> occupied;
    bool inside(glm::ivec3 c) const { return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < n && c.y < n && c.z < n; }
    size_t index(glm::ivec3 c) const { return (size_t(c.z) * size_t(n) + size_t(c.y)) * size_t(n) + size_t(c.x); }
    glm::ivec3 cellOf(glm::vec3 p) const { return glm::ivec3(glm::floor((p - min) / cell)); }
    void mark(glm::vec3 p) {
        glm::ivec3 c = cellOf(p);
        if (inside(c)) occupied[index(c)] = 1;
    }
};

// The subdivisions of a triangle whose points lie at most `spacing` apart, and the points that makes.
int subdivisions(glm::vec3 a, glm::vec3 b, glm::vec3 c, float spacing) {
    float edge = std::max(glm::length(b - a), std::max(glm::length(c - b), glm::length(a - c)));
    float n = std::ceil(edge / spacing);
    return n >= 1.0f ? int(std::min(n, float(4 * kFreePathGrid))) : 1;  // NaN-safe
}
size_t trianglePoints(int n) { return size_t(n + 1) * size_t(n + 2) / 2; }

// Every cell the triangle touches, from points `spacing` apart (half a cell unless the scene's
// area is too large for the point budget).
size_t markTriangle(Grid& g, glm::vec3 a, glm::vec3 b, glm::vec3 c, float spacing) {
    int n = subdivisions(a, b, c, spacing);
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) g.mark(a + (b - a) * (float(i) / float(n)) + (c - a) * (float(j) / float(n)));
    return trianglePoints(n);
}

// Where the ray o + t d leaves the cube (o inside it).
float exitDistance(const Grid& g, glm::vec3 o, glm::vec3 d) {
    float size = g.cell * float(g.n);
    float t = 1e30f;
    for (int k = 0; k < 3; ++k) {
        if (d[k] > 0.0f) t = std::min(t, (g.min[k] + size - o[k]) / d[k]);
        else if (d[k] < 0.0f) t = std::min(t, (g.min[k] - o[k]) / d[k]);
    }
    return std::max(t, 0.0f);
}

// The distance from o along unit d to the first occupied cell (Amanatides and Woo's traversal),
// or to the cube's boundary; `hit` says which.
float march(const Grid& g, glm::vec3 o, glm::vec3 d, bool& hit) {
    hit = false;
    float tExit = exitDistance(g, o, d);
    if (tExit <= 0.0f) return tExit;
    glm::ivec3 c = glm::clamp(g.cellOf(o), glm::ivec3(0), glm::ivec3(g.n - 1));
    glm::ivec3 step(0);
    glm::vec3 tMax(1e30f), tDelta(1e30f);
    for (int k = 0; k < 3; ++k) {
        if (d[k] > 0.0f) {
            step[k] = 1;
            tMax[k] = (g.min[k] + float(c[k] + 1) * g.cell - o[k]) / d[k];
            tDelta[k] = g.cell / d[k];
        } else if (d[k] < 0.0f) {
            step[k] = -1;
            tMax[k] = (g.min[k] + float(c[k]) * g.cell - o[k]) / d[k];
            tDelta[k] = -g.cell / d[k];
        }
    }
    float t = 0.0f;
    while (g.inside(c) && t < tExit) {
        if (g.occupied[g.index(c)]) {
            hit = true;
            return t;
        }
        int k = tMax.x < tMax.y ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
        t = tMax[k];
        tMax[k] += tDelta[k];
        c[k] += step[k];
    }
    return tExit;
}

}  // namespace

FreePath meanFreePath(const Scene& scene) {
    FreePath result;
    if (!scene.bounds.valid()) return result;
    const float size = scene.bounds.gridCubeSize();
    if (!std::isfinite(size)) return result;
    Grid g;
    g.cell = size / float(g.n);
    g.min = scene.bounds.gridCubeMin();
    g.occupied.assign(size_t(g.n) * size_t(g.n) * size_t(g.n), 0);
    result.cubeSize = size;

    const size_t triangles = scene.indices.size() / 3;
    // Which triangles light leaves on both sides: those of double-sided materials.
    std::vector<uint8_t> twoSided(triangles, 0);
    for (const Draw& d : scene.draws)
        if (d.material >= 0 && size_t(d.material) < scene.materials.size() && scene.materials[size_t(d.material)].doubleSided)
            for (uint32_t i = d.firstIndex / 3; i < (d.firstIndex + d.indexCount) / 3 && i < triangles; ++i) twoSided[i] = 1;
    auto corner = [&](size_t t, int k) { return scene.vertices[scene.indices[3 * t + size_t(k)]].position; };
    // Half a cell between points, unless that makes more than kFreePathPointBudget (many large
    // triangles, as a hostile file may hold): then a spacing that fits, which may leave holes in
    // the occupancy and so read the free path long, towards the techniques' own resolution.
    float spacing = 0.5f * g.cell;
    double points = 0.0;
    for (size_t t = 0; t < triangles; ++t) points += double(trianglePoints(subdivisions(corner(t, 0), corner(t, 1), corner(t, 2), spacing)));
    if (points > double(kFreePathPointBudget)) spacing *= float(std::sqrt(points / double(kFreePathPointBudget)));
    std::vector<double> cumulative(triangles);
    double area = 0.0;
    for (size_t t = 0; t < triangles; ++t) {
        glm::vec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
        if (result.points < kFreePathPointBudget) result.points += markTriangle(g, a, b, c, spacing);
        area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        cumulative[t] = area;
    }
    if (!(area > 0.0)) return result;

    PCG32 rng(0, 0);
    double sum = 0.0, hitSum = 0.0;
    int hits = 0;
    for (int r = 0; r < kFreePathRays; ++r) {
        double pick = double(rng.uniform()) * area;
        size_t t = size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
        t = std::min(t, triangles - 1);
        glm::vec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
        glm::vec3 n = glm::cross(b - a, c - a);
        float len = glm::length(n);
        if (!(len > 0.0f)) continue;  // a zero-area triangle is never picked; guards rounding
        n /= len;
        float su = std::sqrt(rng.uniform()), v = rng.uniform();
        glm::vec3 o = a + (b - a) * (su * (1.0f - v)) + (c - a) * (su * v);  // uniform on the triangle
        // The side the authored normals face (a room's walls face in), or either side of a
        // double-sided surface.
        glm::vec3 shading = scene.vertices[scene.indices[3 * t]].normal + scene.vertices[scene.indices[3 * t + 1]].normal +
                            scene.vertices[scene.indices[3 * t + 2]].normal;
        float side = rng.uniform();
        if (twoSided[t] ? side < 0.5f : glm::dot(shading, n) < 0.0f) n = -n;
        // Cosine-distributed direction about n.
        float u1 = rng.uniform(), phi = 6.28318531f * rng.uniform();
        float sinTheta = std::sqrt(u1), cosTheta = std::sqrt(1.0f - u1);
        glm::vec3 tx, ty;
        basis(n, tx, ty);
        glm::vec3 d = glm::normalize(tx * (sinTheta * std::cos(phi)) + ty * (sinTheta * std::sin(phi)) + n * cosTheta);
        // Start 1.5 cells above the own surface, so the ray does not meet the cells it leaves
        // (leaving along the ray instead would start a grazing ray past a nearby wall, or back
        // in its own surface's cells), and measure from the surface point.
        glm::vec3 start = o + n * (1.5f * g.cell);
        bool hit = false;
        float along = march(g, start, d, hit);
        double dist = double(glm::length(start + d * along - o));
        sum += dist;
        if (hit) hitSum += dist;
        hits += hit ? 1 : 0;
        ++result.rays;
    }
    if (result.rays > 0) {
        result.meanDistance = float(sum / double(result.rays));
        result.hitFraction = float(hits) / float(result.rays);
        result.meanHitDistance = hits > 0 ? float(hitSum / double(hits)) : 0.0f;
    }
    return result;
}

}  // namespace gi
