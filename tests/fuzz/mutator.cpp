#include "mutator.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace gi::fuzz {

namespace {

uint32_t u32At(const std::vector<uint8_t>& b, size_t at) {
    uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

void putU32(std::vector<uint8_t>& b, uint32_t v) {
    uint8_t p[4];
    std::memcpy(p, &v, 4);
    b.insert(b.end(), p, p + 4);
}

// Numbers that break range arithmetic: zero, signs, powers of two at type limits, the wrapped
// offsets hostile files use, huge floats.
json interestingNumber(std::mt19937_64& rng, const json& current) {
    static const std::vector<json> values = {
        0, 1, -1, 2, 3, 4, 7, 8, 255, 256, 65535, 65536, 2147483647, 2147483648ull, -2147483648ll, 4294967295ull,
        4294967296ull, 4294967297ull, 1000000000, 9007199254740993ull, 9223372036854775807ull, 9223372036854775808ull,
        18446744073709551604ull, 18446744073709551615ull, 0.5, -0.0, 1e9, 1e15, 1e20, 1e38, -1e38, 3.5e38, 1e300, -1e300};
    std::uniform_int_distribution<size_t> pick(0, values.size() + 3);
    size_t k = pick(rng);
    if (k < values.size()) return values[k];
    // Neighbours of the current value: integers in wrapping 64-bit arithmetic (the wrap is the
    // point), floats as they are.
    if (current.is_number_integer()) {
        bool isUnsigned = current.is_number_unsigned();
        uint64_t u = isUnsigned ? current.get<uint64_t>() : uint64_t(current.get<int64_t>());
        uint64_t next = k == values.size() ? u + 1 : k == values.size() + 1 ? u - 1 : k == values.size() + 2 ? u * 1000 : rng() % 64;
        return isUnsigned ? json(next) : json(int64_t(next));
    }
    double v = current.is_number() ? current.get<double>() : 1.0;
    switch (k - values.size()) {
        case 0: return json(v * 1.0001);
        case 1: return json(-v);
        case 2: return json(v * 1e6);
        default: return json(int64_t(rng() % 64));
    }
}

void collect(const json& j, const json::json_pointer& at, std::vector<json::json_pointer>& all) {
    all.push_back(at);
    if (j.is_object())
        for (auto it = j.begin(); it != j.end(); ++it) collect(it.value(), at / it.key(), all);
    else if (j.is_array())
        for (size_t i = 0; i < j.size(); ++i) collect(j[i], at / i, all);
}

template <class T>
const T& pickFrom(const std::vector<T>& v, std::mt19937_64& rng) {
    return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
}

size_t below(std::mt19937_64& rng, size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(rng); }

// Keys whose values index another array of the file.
// The length of the document's top-level array `key` (0 when it is missing or no array: the
// libFuzzer harness hands in documents that earlier edits broke).
size_t arraySize(const json& doc, const char* key) {
    return doc.is_object() && doc.contains(key) && doc[key].is_array() ? doc[key].size() : 0;
}

bool isReferenceKey(const std::string& key) {
    static const char* keys[] = {"bufferView", "buffer", "indices", "material", "mesh", "camera", "source", "index", "sampler",
                                 "POSITION", "NORMAL", "TEXCOORD_0", "TEXCOORD_1", "TANGENT", "scene", "light", "texCoord"};
    for (const char* k : keys)
        if (key == k) return true;
    return false;
}

}  // namespace

GLTFSeed parseSeed(const std::vector<uint8_t>& b, const std::string& name) {
    if (b.size() < 20 || std::memcmp(b.data(), "glTF", 4) != 0) throw std::runtime_error(name + ": not a GLB");
    size_t jsonLength = u32At(b, 12);
    if (jsonLength > b.size() - 20) throw std::runtime_error(name + ": JSON chunk past the end");
    GLTFSeed s;
    s.name = name;
    s.doc = json::parse(b.begin() + 20, b.begin() + 20 + std::ptrdiff_t(jsonLength));  // throws json::exception
    size_t at = 20 + jsonLength;
    if (at + 8 <= b.size()) {
        size_t binLength = u32At(b, at);
        if (binLength > b.size() - at - 8) throw std::runtime_error(name + ": BIN chunk past the end");
        s.bin.assign(b.begin() + std::ptrdiff_t(at + 8), b.begin() + std::ptrdiff_t(at + 8 + binLength));
    }
    return s;
}

GLTFSeed readSeed(const std::filesystem::path& glb) {
    std::ifstream in(glb, std::ios::binary);
    std::vector<uint8_t> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parseSeed(b, glb.filename().string());
}

std::vector<GLTFSeed> readSeeds(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(folder))
        if (e.path().extension() == ".glb") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    std::vector<GLTFSeed> seeds;
    for (const auto& f : files) seeds.push_back(readSeed(f));
    return seeds;
}

FuzzInput applyEdits(const GLTFSeed& seed, const json& edits) {
    json doc = seed.doc;
    std::vector<uint8_t> bin = seed.bin;
    bool text = false;
    std::vector<std::pair<size_t, uint32_t>> raw;
    for (const json& e : edits) {
        std::string op = e.at("op");
        try {
            if (op == "set") {
                doc[json::json_pointer(e.at("path").get<std::string>())] = e.at("value");
            } else if (op == "remove") {
                json::json_pointer p(e.at("path").get<std::string>());
                if (!p.empty() && doc.contains(p)) {
                    json& parent = doc[p.parent_pointer()];
                    if (parent.is_object()) parent.erase(p.back());
                    else if (parent.is_array()) parent.erase(size_t(std::stoul(p.back())));
                }
            } else if (op == "bin") {
                size_t at = e.at("at");
                for (const auto& v : e.at("bytes"))
                    if (at < bin.size()) bin[at++] = uint8_t(v.get<int>());
            } else if (op == "binSize") {
                bin.resize(std::min<size_t>(e.at("value").get<size_t>(), seed.bin.size() * 2 + 64), 0);
            } else if (op == "raw") {
                raw.push_back({e.at("at").get<size_t>(), e.at("u32").get<uint32_t>()});
            } else if (op == "text") {
                text = true;
            }
        } catch (const json::exception&) {
            // An edit that does not apply to this document (a path through a number) is skipped.
        }
    }
    FuzzInput out;
    if (text) {
        if (doc.contains("buffers") && doc["buffers"].is_array() && !doc["buffers"].empty() && doc["buffers"][0].is_object())
            doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
        std::string s = doc.dump();
        out.bytes.assign(s.begin(), s.end());
        out.binary = false;
    } else {
        std::string js = doc.dump();
        while (js.size() % 4) js += ' ';
        std::vector<uint8_t> padded = bin;
        while (padded.size() % 4) padded.push_back(0);
        std::vector<uint8_t>& b = out.bytes;
        b.insert(b.end(), {'g', 'l', 'T', 'F'});
        putU32(b, 2);
        putU32(b, uint32_t(12 + 8 + js.size() + (padded.empty() ? 0 : 8 + padded.size())));
        putU32(b, uint32_t(js.size()));
        b.insert(b.end(), {'J', 'S', 'O', 'N'});
        b.insert(b.end(), js.begin(), js.end());
        if (!padded.empty()) {
            putU32(b, uint32_t(padded.size()));
            b.insert(b.end(), {'B', 'I', 'N', 0});
            b.insert(b.end(), padded.begin(), padded.end());
        }
    }
    for (auto [at, v] : raw)
        if (at + 4 <= out.bytes.size()) std::memcpy(out.bytes.data() + at, &v, 4);
    return out;
}

json randomEdits(const GLTFSeed& seed, std::mt19937_64& rng) {
    std::vector<json::json_pointer> all;
    collect(seed.doc, json::json_pointer(), all);
    std::vector<json::json_pointer> numbers, references;
    for (const auto& p : all) {
        const json& v = seed.doc[p];
        if (v.is_number()) numbers.push_back(p);
        if (!p.empty() && isReferenceKey(p.back())) references.push_back(p);
        if (!p.empty() && !p.parent_pointer().empty() && p.parent_pointer().back() == "children") references.push_back(p);
    }
    json edits = json::array();
    int count = 1 + int(below(rng, 4));
    for (int n = 0; n < count; ++n) {
        switch (below(rng, 12)) {
            case 0:
            case 1:  // any number
                if (!numbers.empty()) {
                    const auto& p = pickFrom(numbers, rng);
                    edits.push_back({{"op", "set"}, {"path", p.to_string()}, {"value", interestingNumber(rng, seed.doc[p])}});
                }
                break;
            case 2:  // a reference pointed past its array, at -1, or at a neighbour
                if (!references.empty()) {
                    const auto& p = pickFrom(references, rng);
                    static const std::vector<json> targets = {-1, 0, 1, 2, 3, 5, 17, 2147483647, 4294967296ull};
                    edits.push_back({{"op", "set"}, {"path", p.to_string()}, {"value", pickFrom(targets, rng)}});
                }
                break;
            case 3: {  // a sparse block on an accessor
                size_t accessors = arraySize(seed.doc, "accessors");
                size_t views = std::max<size_t>(arraySize(seed.doc, "bufferViews"), 1);
                static const std::vector<int> types = {5121, 5123, 5125, 5126, 5120};
                json sparse = {{"count", interestingNumber(rng, json(4))},
                               {"indices", {{"bufferView", int(below(rng, views + 1))}, {"byteOffset", interestingNumber(rng, json(0))},
                                            {"componentType", pickFrom(types, rng)}}},
                               {"values", {{"bufferView", int(below(rng, views + 1))}, {"byteOffset", int(below(rng, 64))}}}};
                if (below(rng, 2)) sparse["count"] = int(1 + below(rng, 8));
                edits.push_back({{"op", "set"}, {"path", "/accessors/" + std::to_string(below(rng, accessors)) + "/sparse"}, {"value", sparse}});
                break;
            }
            case 4:  // remove a key or element
                if (all.size() > 1) edits.push_back({{"op", "remove"}, {"path", all[1 + below(rng, all.size() - 1)].to_string()}});
                break;
            case 5: {  // flip buffer bytes, or write a float that is garbage but finite
                if (seed.bin.empty()) break;
                size_t at = below(rng, seed.bin.size());
                json bytes = json::array();
                if (below(rng, 2)) {
                    float f = below(rng, 2) ? 3.0e38f : (below(rng, 2) ? 1e5f : -7.5e12f);
                    uint8_t p[4];
                    std::memcpy(p, &f, 4);
                    for (uint8_t c : p) bytes.push_back(c);
                } else {
                    for (size_t k = 0, n = 1 + below(rng, 8); k < n; ++k) bytes.push_back(int(rng() & 255));
                }
                edits.push_back({{"op", "bin"}, {"at", at}, {"bytes", bytes}});
                break;
            }
            case 6: {  // an image header: PNG width/height, chunk lengths, JPEG markers
                size_t images = arraySize(seed.doc, "images");
                if (images == 0) break;
                const json& img = seed.doc["images"][below(rng, images)];
                if (!img.is_object() || !img.contains("bufferView") || !img["bufferView"].is_number_unsigned()) break;
                size_t viewIndex = img["bufferView"].get<size_t>();
                if (viewIndex >= arraySize(seed.doc, "bufferViews") || !seed.doc["bufferViews"][viewIndex].is_object()) break;
                const json& offset = seed.doc["bufferViews"][viewIndex].value("byteOffset", json(0));
                size_t start = offset.is_number_unsigned() ? offset.get<size_t>() : 0;
                static const std::vector<size_t> fields = {8, 12, 16, 20, 24, 25, 28, 33, 37};
                uint32_t v = below(rng, 2) ? 0xFFFFFF7Fu : uint32_t(rng());
                uint8_t p[4];
                std::memcpy(p, &v, 4);
                edits.push_back({{"op", "bin"}, {"at", start + pickFrom(fields, rng)}, {"bytes", {p[0], p[1], p[2], p[3]}}});
                break;
            }
            case 7:  // the buffer cut short or grown
                edits.push_back({{"op", "binSize"}, {"value", below(rng, seed.bin.size() + 16)}});
                break;
            case 8: {  // the GLB container's lengths
                static const std::vector<size_t> at = {8, 12, 16};
                edits.push_back({{"op", "raw"}, {"at", below(rng, 3) == 0 ? below(rng, 64) : pickFrom(at, rng)},
                                 {"u32", below(rng, 2) ? uint32_t(rng()) : uint32_t(0xFFFFFFF0u + below(rng, 16))}});
                break;
            }
            case 9: {  // an accessor's type or component type
                size_t accessors = arraySize(seed.doc, "accessors");
                if (!accessors) break;
                std::string a = "/accessors/" + std::to_string(below(rng, accessors));
                static const std::vector<json> types = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT4", "VEC9", 3};
                static const std::vector<json> componentTypes = {5120, 5121, 5122, 5123, 5125, 5126, 5124, 0, -1};
                if (below(rng, 2)) edits.push_back({{"op", "set"}, {"path", a + "/type"}, {"value", pickFrom(types, rng)}});
                else edits.push_back({{"op", "set"}, {"path", a + "/componentType"}, {"value", pickFrom(componentTypes, rng)}});
                if (below(rng, 3) == 0) edits.push_back({{"op", "set"}, {"path", a + "/normalized"}, {"value", true}});
                break;
            }
            case 10: {  // the node hierarchy: shared children, cycles, degenerate transforms
                size_t nodes = arraySize(seed.doc, "nodes");
                if (!nodes) break;
                std::string n = "/nodes/" + std::to_string(below(rng, nodes));
                switch (below(rng, 4)) {
                    case 0: {
                        json children = json::array();
                        for (size_t k = 0, m = 1 + below(rng, 40); k < m; ++k) children.push_back(int(below(rng, nodes + 1)));
                        edits.push_back({{"op", "set"}, {"path", n + "/children"}, {"value", children}});
                        break;
                    }
                    case 1: edits.push_back({{"op", "set"}, {"path", n + "/scale"}, {"value", {0, 0, 0}}}); break;
                    case 2: edits.push_back({{"op", "set"}, {"path", n + "/matrix"}, {"value", json::array({1e38, 0, 0, 0, 0, 1e38, 0, 0, 0, 0, 1e38, 0, 0, 0, 0, 1})}}); break;
                    default: edits.push_back({{"op", "set"}, {"path", n + "/rotation"}, {"value", {0, 0, 0, 0}}}); break;
                }
                break;
            }
            default:  // written as .gltf with the buffer as a data URI
                edits.push_back({{"op", "text"}});
                break;
        }
    }
    return edits;
}

std::string mutatePreset(const std::string& text, std::mt19937_64& rng) {
    json doc = json::parse(text, nullptr, false);
    if (doc.is_discarded() || below(rng, 8) == 0) {
        // Bytes: flipped, cut or duplicated, for the JSON parser.
        std::string s = text;
        if (s.empty()) return "{";
        switch (below(rng, 3)) {
            case 0:
                for (size_t k = 0, n = 1 + below(rng, 4); k < n; ++k) s[below(rng, s.size())] = char(rng() & 255);
                break;
            case 1: s.resize(below(rng, s.size())); break;
            default: s = std::string(below(rng, 4000), '[') + s; break;
        }
        return s;
    }
    std::vector<json::json_pointer> all;
    collect(doc, json::json_pointer(), all);
    for (int n = 0, count = 1 + int(below(rng, 3)); n < count; ++n) {
        const auto& p = pickFrom(all, rng);
        // An earlier edit may have removed or retyped this path's parent.
        if (p.empty() || !doc.contains(p)) continue;
        json& v = doc[p];
        switch (below(rng, 6)) {
            case 0: v = interestingNumber(rng, v); break;
            case 1: v = pickFrom(std::vector<json>{"", "x", "builtin:sky", "cornell", "../../etc/passwd", ".", "{face}", json::array(), json::object(), nullptr, true}, rng); break;
            case 2: {
                json& parent = doc[p.parent_pointer()];
                if (parent.is_object()) parent.erase(p.back());
                break;
            }
            case 3: {
                json& parent = doc[p.parent_pointer()];
                if (parent.is_object()) parent["unknownKey" + std::to_string(below(rng, 3))] = 1;
                break;
            }
            case 4: v = json::array({v, v, v}); break;
            default: if (v.is_array() && !v.empty()) v.push_back(v[0]); else v = interestingNumber(rng, v); break;
        }
    }
    return doc.dump();
}

std::string base64(const std::vector<uint8_t>& data) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < data.size(); i += 3) {
        uint32_t v = uint32_t(data[i]) << 16;
        if (i + 1 < data.size()) v |= uint32_t(data[i + 1]) << 8;
        if (i + 2 < data.size()) v |= data[i + 2];
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += i + 1 < data.size() ? t[(v >> 6) & 63] : '=';
        out += i + 2 < data.size() ? t[v & 63] : '=';
    }
    return out;
}

std::mt19937_64 iterationRng(uint64_t seed, uint64_t i) {
    std::seed_seq seq{uint32_t(seed), uint32_t(seed >> 32), uint32_t(i), uint32_t(i >> 32)};
    return std::mt19937_64(seq);
}

}  // namespace gi::fuzz
