// Deterministic sampling on the CPU, shared by the path tracer (gi/reference) and the scene's
// free-path measure (gi/scene/free_path): the same numbers on every platform, unlike the standard
// library's distributions.
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>

namespace gi {

// PCG32 (O'Neill 2014): small state, good quality, cheap to seed per sample.
struct PCG32 {
    uint64_t state = 0, inc = 1;
    PCG32(uint64_t seed, uint64_t stream) {
        inc = (stream << 1u) | 1u;
        next();
        state += seed;
        next();
    }
    uint32_t next() {
        uint64_t old = state;
        state = old * 6364136223846793005ULL + inc;
        uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
    }
    float uniform() { return float(next() >> 8) * 0x1p-24f; }  // [0, 1)
};

// An orthonormal basis around unit n (Duff et al. 2017).
inline void basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float bb = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    b = glm::vec3(bb, sign + n.y * n.y * a, -n.y);
}

}  // namespace gi
