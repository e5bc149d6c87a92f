// libFuzzer harness of the glTF loader (built with clang when libFuzzer is available):
//   build-asan/tests/gi-libfuzzer-gltf -max_total_time=600 -rss_limit_mb=2048 CORPUS_DIR tests/fuzz/corpus
// Inputs load or fail with gi::Error; anything else is a finding. The custom mutator applies the
// structure-aware edits of tests/fuzz/mutator.h to inputs that are GLBs, and libFuzzer's byte
// mutations to the rest.
#include "mutator.h"

#include "gi/scene/scene.h"
#include "gi/util/error.h"

#include <cstring>

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t maxSize);

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<uint8_t> bytes(data, data + size);
    bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    try {
        gi::loadGLTFFromMemory(bytes, binary, binary ? "fuzz.glb" : "fuzz.gltf", std::string(GI_SOURCE_DIR) + "/tests/fuzz/corpus", 256.0);
    } catch (const gi::Error&) {
    }
    return 0;
}

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t maxSize, unsigned int seed) {
    std::mt19937_64 rng(seed);
    if (rng() % 4 != 0) {
        try {
            gi::fuzz::GLTFSeed s = gi::fuzz::parseSeed(std::vector<uint8_t>(data, data + size), "input");
            gi::fuzz::FuzzInput in = gi::fuzz::applyEdits(s, gi::fuzz::randomEdits(s, rng));
            if (in.bytes.size() <= maxSize) {
                std::memcpy(data, in.bytes.data(), in.bytes.size());
                return in.bytes.size();
            }
        } catch (const std::exception&) {
        }
    }
    return LLVMFuzzerMutate(data, size, maxSize);
}
