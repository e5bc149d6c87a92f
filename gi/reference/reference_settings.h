// Settings of the path-traced reference.
#pragma once

#include "gi/preset/settings.h"

namespace gi {

enum class ReferenceMode { Full, Direct, Indirect };
template <>
struct EnumNames<ReferenceMode> {
    static constexpr std::array<std::pair<ReferenceMode, const char*>, 3> values{
        {{ReferenceMode::Full, "full"}, {ReferenceMode::Direct, "direct"}, {ReferenceMode::Indirect, "indirect"}}};
};

struct ReferenceSettings {
    static constexpr std::string_view kSection = "reference";
    int spp = 256;                          // samples per pixel
    int maxBounces = 8;                     // surface bounces after the camera ray; 1 = direct light only
    ReferenceMode mode = ReferenceMode::Full;  // full, direct (one bounce) or indirect (two or more)
    int seed = 1;                           // random sequence; the same seed gives the same image
    int rouletteDepth = 3;                  // bounces before Russian roulette may end a path

    template <class V>
    void visit(V&& v) {
        v(spp, {"spp", "Samples per pixel of the path-traced reference", "", 1, 1 << 16, Cost::Reallocate});
        v(maxBounces, forDevelopers({"maxBounces", "Maximum surface bounces per path", "", 1, 64, Cost::Reallocate}));
        v(mode, forDevelopers({"mode", "Light paths kept: full, direct (one bounce) or indirect (two or more bounces)", "", 0, 0,
                 Cost::Reallocate}));
        v(seed, forDevelopers({"seed", "Random seed of the reference", "", 0, 1 << 30, Cost::Reallocate}));
        v(rouletteDepth, forDevelopers({"rouletteDepth", "Bounces before Russian roulette starts", "", 1, 64, Cost::Reallocate}));
    }
};

}  // namespace gi
