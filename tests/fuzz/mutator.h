// Structure-aware mutation of glTF files and presets for the fuzzers (tests/fuzz/gi_fuzz.cpp, the
// libFuzzer harnesses and tests/gltf_hostile_test.cpp).
//
// A glTF seed is a self-contained GLB (tests/fuzz/corpus/): its JSON, its BIN chunk and the
// images in buffer views. A mutation is a short list of edits, each a JSON object, so any input
// the fuzzers try can be printed, replayed and kept as a regression case
// (tests/fuzz/regressions.json):
//   {"op": "set", "path": "/accessors/0/count", "value": 4294967297}   JSON pointer; extends arrays
//   {"op": "remove", "path": "/images/0/mimeType"}
//   {"op": "bin", "at": 1234, "bytes": [255, 0, 17]}                   overwrite BIN bytes
//   {"op": "binSize", "value": 100}                                     truncate or extend BIN
//   {"op": "raw", "at": 12, "u32": 4294967295}                          overwrite the final file's bytes
//   {"op": "text"}                                                      write .gltf JSON with a data URI
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace gi::fuzz {

using json = nlohmann::json;

struct GLTFSeed {
    std::string name;
    json doc;
    std::vector<uint8_t> bin;
};

// A file to load: the bytes and whether they are a GLB.
struct FuzzInput {
    std::vector<uint8_t> bytes;
    bool binary = true;
};

// Splits a GLB into its JSON and BIN chunks. Throws std::exception for a malformed one.
GLTFSeed parseSeed(const std::vector<uint8_t>& glb, const std::string& name);
GLTFSeed readSeed(const std::filesystem::path& glb);
std::vector<GLTFSeed> readSeeds(const std::filesystem::path& folder);

// Applies `edits` to the seed and serialises it.
FuzzInput applyEdits(const GLTFSeed& seed, const json& edits);

// One to four random edits for `seed`, drawn from `rng` (deterministic for a given state).
json randomEdits(const GLTFSeed& seed, std::mt19937_64& rng);

// A preset text mutated from `text` (shipped presets are the seeds): JSON values replaced,
// removed, retyped or duplicated, unknown keys added, or the text's bytes flipped.
std::string mutatePreset(const std::string& text, std::mt19937_64& rng);

// RFC 4648 base64, for data URIs.
std::string base64(const std::vector<uint8_t>& data);

// The generator of iteration `i` of a run with `seed`: iterations are independent, so one can be
// replayed alone.
std::mt19937_64 iterationRng(uint64_t seed, uint64_t i);

}  // namespace gi::fuzz
