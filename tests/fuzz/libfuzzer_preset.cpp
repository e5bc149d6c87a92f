// libFuzzer harness of the preset parser (built with clang when libFuzzer is available):
//   build-asan/tests/gi-libfuzzer-preset -max_total_time=600 CORPUS_DIR presets
// Presets parse, resolve against their built-in scene and pass the budget check, or fail with
// gi::Error; anything else is a finding. The custom mutator edits the JSON structurally.
#include "mutator.h"

#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/scene.h"
#include "gi/util/error.h"

#include <cstring>

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t maxSize);

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        gi::Preset p = gi::presetFromText(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
        if (gi::isBuiltinScene(p.header.scene)) {
            gi::Scene scene = gi::makeBuiltinScene(p.header.scene);
            gi::Renderer::checkBudget(gi::frameSettings(p, scene, 64, 64), scene);
        }
    } catch (const gi::Error&) {
    }
    return 0;
}

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t maxSize, unsigned int seed) {
    std::mt19937_64 rng(seed);
    if (rng() % 4 == 0) return LLVMFuzzerMutate(data, size, maxSize);
    std::string text = gi::fuzz::mutatePreset(std::string(reinterpret_cast<const char*>(data), size), rng);
    size_t n = std::min(text.size(), maxSize);
    std::memcpy(data, text.data(), n);
    return n;
}
