#include "gi/matrix/matrix.h"

#include "gi/preset/preset.h"
#include "gi/util/error.h"
#include "gi/util/hash.h"
#include "gi/util/paths.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace gi::matrix {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A settings value as --set takes it: strings bare, everything else as JSON.
std::string valueText(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

std::vector<std::string> assignments(const json& set, const std::string& where) {
    if (!set.is_object()) throw Error(where + ": expected an object of \"key\": value");
    std::vector<std::string> out;
    for (auto it = set.begin(); it != set.end(); ++it) out.push_back(it.key() + "=" + valueText(it.value()));
    return out;
}

// Applies the overrides to a default preset, so an unknown key or a value out of range is
// reported with the spec's name before any cell runs. Lights depend on the scene's own preset;
// gi-render checks those.
void validate(const std::vector<std::string>& set, const std::string& where) {
    Preset p = builtinDefaultPreset();
    for (const std::string& a : set) {
        if (a.rfind("lights.", 0) == 0) continue;
        try {
            applySetting(p, a);
        } catch (const Error& e) {
            std::string message = e.what();
            if (message.rfind("--set: ", 0) == 0) message = message.substr(7);
            throw Error(where + ": " + message);
        }
    }
}

std::vector<std::string> techniqueNames() {
    for (const SettingInfo& s : listSettings())
        if (s.key == "technique") return s.choices;
    return {};
}

void checkKeys(const json& j, std::initializer_list<const char*> known, const std::string& where) {
    for (auto it = j.begin(); it != j.end(); ++it)
        if (std::find_if(known.begin(), known.end(), [&](const char* k) { return it.key() == k; }) == known.end()) {
            std::string list;
            for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
            throw Error(where + ": unknown key '" + it.key() + "' (expected one of " + list + ")");
        }
}

template <class T>
T number(const json& j, const char* key, T fallback, double lo, double hi, const std::string& where) {
    if (!j.contains(key)) return fallback;
    const json& v = j[key];
    if (!v.is_number()) throw Error(where + ": '" + key + "' must be a number");
    double d = v.get<double>();
    if (!(d >= lo && d <= hi)) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "' is %g, outside [%g, %g]", d, lo, hi);
        throw Error(where + ": '" + key + buf);
    }
    if (std::is_integral_v<T> && d != std::floor(d)) throw Error(where + ": '" + key + "' must be a whole number");
    return T(d);
}

std::string inputPath(const std::string& input, const fs::path& folder) {
    if (input.empty() || input == "default") return "";
    fs::path p(input);
    if (p.is_relative() && !folder.empty() && fs::exists(folder / p)) p = folder / p;
    if (!fs::exists(p)) {
        // As gi-render finds assets: the search path (../shared/scenes and friends).
        p = resolveAsset(input, folder);
    }
    return fs::absolute(p).lexically_normal().string();
}

std::vector<std::string> sweepValues(const json& v, const std::string& where) {
    std::vector<std::string> out;
    if (v.is_array()) {
        for (const json& e : v) out.push_back(valueText(e));
    } else if (v.is_object()) {
        checkKeys(v, {"from", "to", "step"}, where);
        double from = number<double>(v, "from", NAN, -1e12, 1e12, where), to = number<double>(v, "to", NAN, -1e12, 1e12, where);
        double step = number<double>(v, "step", 1.0, 1e-9, 1e12, where);
        if (std::isnan(from) || std::isnan(to)) throw Error(where + ": a range needs 'from' and 'to'");
        if (to < from) throw Error(where + ": 'to' is below 'from'");
        double n = std::floor((to - from) / step + 1e-9) + 1.0;
        if (n > double(kMaxCells)) throw Error(where + ": the range has more than " + std::to_string(kMaxCells) + " values");
        for (double k = 0; k < n; ++k) {
            double x = from + k * step;
            out.push_back(json(x == std::round(x) && std::abs(x) < 1e15 ? json(int64_t(x)) : json(x)).dump());
        }
    } else {
        throw Error(where + ": expected a list of values or {\"from\", \"to\", \"step\"}");
    }
    if (out.empty()) throw Error(where + ": no values");
    return out;
}

std::string hex(uint64_t v, int digits) {
    static const char* d = "0123456789abcdef";
    std::string s(size_t(digits), '0');
    for (int i = digits - 1; i >= 0; --i, v >>= 4) s[size_t(i)] = d[v & 15];
    return s;
}

std::string joined(const std::vector<std::string>& v, const char* sep) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : sep) + x;
    return s;
}

double numberOr(const json& j, const char* key, double fallback = 0.0) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

}  // namespace

std::string slug(const std::string& text) {
    std::string s;
    for (char c : text) s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
    if (s.empty() || s == "." || s == "..") s = "_" + s;
    return s.substr(0, 80);
}

MatrixSpec specFromJson(const json& j, const std::string& context, const fs::path& folder) {
    if (!j.is_object()) throw Error(context + ": expected a JSON object");
    checkKeys(j, {"name", "width", "height", "frames", "spp", "timeoutSeconds", "scenes", "cells"}, context);
    MatrixSpec spec;
    spec.file = context;
    if (j.contains("name")) {
        if (!j["name"].is_string()) throw Error(context + ": 'name' must be a string");
        spec.name = j["name"].get<std::string>();
    }
    spec.width = number<int>(j, "width", spec.width, 1, 16384, context);
    spec.height = number<int>(j, "height", spec.height, 1, 16384, context);
    spec.frames = number<int>(j, "frames", spec.frames, 1, 10000, context);
    spec.spp = number<int>(j, "spp", spec.spp, 1, 65536, context);
    spec.timeoutSeconds = number<double>(j, "timeoutSeconds", spec.timeoutSeconds, 0.001, 1e7, context);

    if (!j.contains("scenes") || !j["scenes"].is_array() || j["scenes"].empty())
        throw Error(context + ": 'scenes' must be a non-empty list");
    std::set<std::string> labels;
    for (size_t i = 0; i < j["scenes"].size(); ++i) {
        const json& s = j["scenes"][i];
        std::string where = context + ": scenes[" + std::to_string(i) + "]";
        SceneSpec scene;
        if (s.is_string()) {
            scene.input = inputPath(s.get<std::string>(), folder);
        } else if (s.is_object()) {
            checkKeys(s, {"input", "label", "camera", "set"}, where);
            if (s.contains("input") && !s["input"].is_string()) throw Error(where + ": 'input' must be a string");
            scene.input = inputPath(s.value("input", std::string()), folder);
            if (s.contains("label") && !s["label"].is_string()) throw Error(where + ": 'label' must be a string");
            scene.label = s.value("label", std::string());
            scene.camera = number<int>(s, "camera", -1, -1, 1023, where);
            if (s.contains("set")) scene.set = assignments(s["set"], where + ".set");
            validate(scene.set, where + ".set");
        } else {
            throw Error(where + ": expected a path or an object with 'input'");
        }
        if (scene.label.empty()) scene.label = scene.input.empty() ? "default" : fs::path(scene.input).stem().string();
        if (!labels.insert(scene.label).second)
            throw Error(where + ": scene label '" + scene.label + "' is used twice (give each a \"label\")");
        spec.scenes.push_back(std::move(scene));
    }

    if (!j.contains("cells") || !j["cells"].is_array() || j["cells"].empty())
        throw Error(context + ": 'cells' must be a non-empty list");
    std::vector<std::string> techniques = techniqueNames();
    for (size_t i = 0; i < j["cells"].size(); ++i) {
        const json& c = j["cells"][i];
        std::string where = context + ": cells[" + std::to_string(i) + "]";
        if (!c.is_object()) throw Error(where + ": expected an object with 'technique'");
        checkKeys(c, {"technique", "label", "set", "sweep", "paperScores", "scenes"}, where);
        VariantSpec v;
        if (!c.contains("technique") || !c["technique"].is_string()) throw Error(where + ": 'technique' must be a string");
        v.technique = c["technique"].get<std::string>();
        if (v.technique != "*" && std::find(techniques.begin(), techniques.end(), v.technique) == techniques.end())
            throw Error(where + ": unknown technique '" + v.technique + "' (expected " + joined(techniques, ", ") + " or *)");
        if (c.contains("label") && !c["label"].is_string()) throw Error(where + ": 'label' must be a string");
        v.label = c.value("label", std::string());
        if (c.contains("set")) v.set = assignments(c["set"], where + ".set");
        for (const std::string& a : v.set)
            if (a.rfind("technique=", 0) == 0) throw Error(where + ".set: name the technique in 'technique', not in 'set'");
        validate(v.set, where + ".set");
        if (c.contains("sweep")) {
            if (!c["sweep"].is_object()) throw Error(where + ": 'sweep' must be an object of \"key\": values");
            for (auto it = c["sweep"].begin(); it != c["sweep"].end(); ++it) {
                Sweep s{it.key(), sweepValues(it.value(), where + ".sweep." + it.key())};
                std::vector<std::string> each;
                for (const std::string& value : s.values) each.push_back(s.key + "=" + value);
                validate(each, where + ".sweep");
                v.sweeps.push_back(std::move(s));
            }
        }
        if (c.contains("scenes")) {
            if (!c["scenes"].is_array() || c["scenes"].empty()) throw Error(where + ": 'scenes' must be a non-empty list of scene labels");
            for (const json& l : c["scenes"]) {
                if (!l.is_string() || !labels.count(l.get<std::string>()))
                    throw Error(where + ".scenes: no scene is labelled " + l.dump());
                v.scenes.push_back(l.get<std::string>());
            }
        }
        if (c.contains("paperScores")) {
            if (!c["paperScores"].is_object()) throw Error(where + ": 'paperScores' must be an object of scene label: score");
            for (auto it = c["paperScores"].begin(); it != c["paperScores"].end(); ++it) {
                if (!it.value().is_number()) throw Error(where + ".paperScores." + it.key() + ": expected a number");
                if (!labels.count(it.key())) throw Error(where + ".paperScores: no scene is labelled '" + it.key() + "'");
                v.paperScores[it.key()] = it.value().get<double>();
            }
        }
        spec.variants.push_back(std::move(v));
    }
    expandCells(spec);  // refuses an oversized product now, not when it runs
    return spec;
}

MatrixSpec loadSpec(const fs::path& path) {
    std::string text = readTextFile(path, size_t(16) << 20);
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        throw Error(path.string() + ": invalid JSON at byte " + std::to_string(e.byte));
    }
    return specFromJson(j, path.string(), path.parent_path());
}

Cell makeCell(const MatrixSpec& spec, size_t sceneIndex, const std::string& technique, const std::string& label,
              const std::vector<std::string>& set) {
    const SceneSpec& scene = spec.scenes.at(sceneIndex);
    Cell c;
    c.scene = sceneIndex;
    c.sceneLabel = scene.label;
    c.technique = technique;
    c.label = label;
    c.set = set;
    std::string key = scene.input + "\n" + std::to_string(scene.camera) + "\n" + joined(scene.set, "\n") + "\n" + technique + "\n" +
                      joined(set, "\n") + "\n" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + "/" +
                      std::to_string(spec.frames) + "/" + std::to_string(spec.spp);
    Hasher hash;
    hash.bytes(key.data(), key.size());
    c.id = slug(label).substr(0, 40) + "-" + hex(hash.result(), 12);
    return c;
}

std::vector<Cell> expandCells(const MatrixSpec& spec) {
    std::vector<Cell> cells;
    std::vector<std::string> all = techniqueNames();
    for (size_t si = 0; si < spec.scenes.size(); ++si) {
        const SceneSpec& scene = spec.scenes[si];
        for (const VariantSpec& v : spec.variants) {
            if (!v.scenes.empty() && std::find(v.scenes.begin(), v.scenes.end(), scene.label) == v.scenes.end()) continue;
            std::vector<std::string> techniques = v.technique == "*" ? all : std::vector<std::string>{v.technique};
            // The sweep's product, the first key varying slowest.
            std::vector<std::vector<std::string>> points{{}};
            for (const Sweep& s : v.sweeps) {
                std::vector<std::vector<std::string>> next;
                for (const auto& p : points)
                    for (const std::string& value : s.values) {
                        next.push_back(p);
                        next.back().push_back(s.key + "=" + value);
                    }
                points = std::move(next);
                if (points.size() * spec.scenes.size() > kMaxCells) break;
            }
            for (const std::string& t : techniques)
                for (const auto& point : points) {
                    std::vector<std::string> set = v.set;
                    set.insert(set.end(), point.begin(), point.end());
                    // The label, or the technique, then what varies: the overrides when there is
                    // no label, the sweep point always.
                    std::string label = v.label.empty() ? t : v.technique == "*" ? v.label + " " + t : v.label;
                    std::vector<std::string> shown = v.label.empty() ? set : point;
                    if (!shown.empty()) label += " " + joined(shown, " ");
                    Cell c = makeCell(spec, si, t, label, set);
                    if (auto it = v.paperScores.find(scene.label); it != v.paperScores.end()) c.paperScore = it->second;
                    cells.push_back(std::move(c));
                    if (cells.size() > kMaxCells)
                        throw Error(spec.file.string() + ": the matrix has more than " + std::to_string(kMaxCells) +
                                    " cells; split it or narrow its sweeps");
                }
        }
    }
    if (cells.empty()) throw Error(spec.file.string() + ": the matrix has no cells (do the variants' 'scenes' name any scene?)");
    std::set<std::string> ids;
    for (const Cell& c : cells)
        if (!ids.insert(c.sceneLabel + "/" + c.id).second)
            throw Error(spec.file.string() + ": scene '" + c.sceneLabel + "' has the cell '" + c.label + "' twice");
    return cells;
}

std::pair<int, int> parseShard(const std::string& text) {
    int i = -1, n = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &tail) != 2 || n < 1 || i < 0 || i >= n)
        throw Error("--shard '" + text + "': expected i/n with 0 <= i < n, e.g. 0/2");
    return {i, n};
}

std::vector<Cell> shardOf(const std::vector<Cell>& cells, int i, int n) {
    if (n < 1 || i < 0 || i >= n) throw Error("--shard: expected 0 <= i < n");
    std::vector<Cell> out;
    for (size_t k = size_t(i); k < cells.size(); k += size_t(n)) out.push_back(cells[k]);
    return out;
}

std::vector<std::string> renderArguments(const MatrixSpec& spec, const Cell& cell, const fs::path& outDir) {
    const SceneSpec& scene = spec.scenes[cell.scene];
    std::vector<std::string> a;
    if (!scene.input.empty()) a.push_back(scene.input);
    a.insert(a.end(), {"--out", outDir.string(), "--width", std::to_string(spec.width), "--height", std::to_string(spec.height),
                       "--frames", std::to_string(spec.frames), "--reference", "--score", "--spp", std::to_string(spec.spp)});
    if (scene.camera >= 0) a.insert(a.end(), {"--camera", std::to_string(scene.camera)});
    a.insert(a.end(), {"--set", "technique=" + cell.technique});
    for (const std::string& s : scene.set) a.insert(a.end(), {"--set", s});
    for (const std::string& s : cell.set) a.insert(a.end(), {"--set", s});
    return a;
}

json resultToJson(const CellResult& r) {
    json passes = json::array();
    for (const auto& [name, ms] : r.passMs) passes.push_back({{"name", name}, {"ms", ms}});
    json j = {{"id", r.id},
              {"scene", r.scene},
              {"technique", r.technique},
              {"label", r.label},
              {"settings", r.settings},
              {"status", r.status},
              {"error", r.error},
              {"ssim", r.ssim},
              {"score", r.score},
              {"rmse", r.rmse},
              {"psnr", r.psnr},
              {"brightness", r.brightness},
              {"leakFraction", r.leakFraction},
              {"leakEnergy", r.leakEnergy},
              {"msTotal", r.msTotal},
              {"msGI", r.msGI},
              {"passes", passes},
              {"memoryBytes", r.memoryBytes},
              {"renderer", r.renderer},
              {"wallSeconds", r.wallSeconds},
              {"folder", r.folder}};
    if (r.paperScore) j["paperScore"] = *r.paperScore;
    return j;
}

CellResult resultOf(const Cell& cell, const std::string& status) {
    CellResult r;
    r.id = cell.id;
    r.scene = cell.sceneLabel;
    r.technique = cell.technique;
    r.label = cell.label;
    r.settings = cell.set;
    r.paperScore = cell.paperScore;
    r.status = status;
    return r;
}

namespace {
// The metrics' keys, as gi-render's stats.json and result.json both name them.
void readMetrics(const json& m, CellResult& r) {
    r.ssim = numberOr(m, "ssim");
    r.score = numberOr(m, "score");
    r.rmse = numberOr(m, "rmse");
    r.psnr = numberOr(m, "psnr");
    r.brightness = numberOr(m, "brightness");
    r.leakFraction = numberOr(m, "leakFraction");
    r.leakEnergy = numberOr(m, "leakEnergy");
}
}  // namespace

CellResult resultFromJson(const json& j, const std::string& context) {
    if (!j.is_object()) throw Error(context + ": expected a JSON object");
    CellResult r;
    try {
        r.id = j.at("id").get<std::string>();
        r.scene = j.at("scene").get<std::string>();
        r.technique = j.at("technique").get<std::string>();
        r.label = j.at("label").get<std::string>();
        r.settings = j.at("settings").get<std::vector<std::string>>();
        r.status = j.at("status").get<std::string>();
        r.error = j.value("error", std::string());
        r.renderer = j.value("renderer", std::string());
        r.folder = j.value("folder", std::string());
        if (j.contains("passes"))
            for (const json& p : j["passes"]) r.passMs.emplace_back(p.at("name").get<std::string>(), p.at("ms").get<double>());
    } catch (const json::exception& e) {
        throw Error(context + ": " + e.what());
    }
    readMetrics(j, r);
    r.msTotal = numberOr(j, "msTotal");
    // Results written before msGI existed: the technique's passes from the pass list.
    if (j.contains("msGI")) r.msGI = numberOr(j, "msGI");
    else
        for (const auto& [name, ms] : r.passMs)
            if (name.rfind(r.technique + ".", 0) == 0) r.msGI += ms;
    r.memoryBytes = numberOr(j, "memoryBytes");
    r.wallSeconds = numberOr(j, "wallSeconds");
    if (j.contains("paperScore") && j["paperScore"].is_number()) r.paperScore = j["paperScore"].get<double>();
    return r;
}

CellResult resultFromStats(const Cell& cell, const fs::path& cellDir) {
    fs::path statsPath = cellDir / "stats.json";
    json stats;
    try {
        stats = json::parse(readTextFile(statsPath, size_t(64) << 20));
    } catch (const json::parse_error& e) {
        throw Error(statsPath.string() + ": invalid JSON at byte " + std::to_string(e.byte));
    }
    if (!stats.contains("metrics") || !stats["metrics"].is_object()) throw Error(statsPath.string() + ": no 'metrics' (was it scored?)");
    CellResult r = resultOf(cell, "ok");
    readMetrics(stats["metrics"], r);
    // The median frame after the first (gi-render's gpuMsMedian), else the last frame.
    r.msTotal = numberOr(stats, "gpuMsMedian", numberOr(stats, "gpuMsTotal"));
    r.memoryBytes = numberOr(stats, "memoryBytes");
    r.renderer = stats.value("renderer", std::string());
    if (stats.contains("passes") && stats["passes"].is_array())
        for (const json& p : stats["passes"])
            if (p.contains("name") && p["name"].is_string()) r.passMs.emplace_back(p["name"].get<std::string>(), numberOr(p, "gpuMs"));
    for (const auto& [name, ms] : r.passMs)
        if (name.rfind(cell.technique + ".", 0) == 0) r.msGI += ms;
    return r;
}

std::vector<CellResult> collectResults(const fs::path& dir) {
    std::vector<CellResult> out;
    fs::path cells = dir / "cells";
    std::error_code ec;
    if (!fs::is_directory(cells, ec)) return out;
    for (auto it = fs::recursive_directory_iterator(cells, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (it->path().filename() != "result.json") continue;
        json j;
        try {
            j = json::parse(readTextFile(it->path(), size_t(16) << 20));
        } catch (const json::parse_error& e) {
            throw Error(it->path().string() + ": invalid JSON at byte " + std::to_string(e.byte));
        }
        out.push_back(resultFromJson(j, it->path().string()));
        out.back().folder = fs::relative(it->path().parent_path(), dir).generic_string();
    }
    std::sort(out.begin(), out.end(), [](const CellResult& a, const CellResult& b) {
        return std::tie(a.scene, a.technique, a.label, a.id) < std::tie(b.scene, b.technique, b.label, b.id);
    });
    return out;
}

std::vector<CellResult> reportedResults(const fs::path& dir) {
    std::vector<CellResult> all = collectResults(dir);
    fs::path listed = dir / "results.json";
    std::error_code ec;
    if (!fs::is_regular_file(listed, ec)) return all;
    std::set<std::pair<std::string, std::string>> named;
    try {
        for (const json& r : json::parse(readTextFile(listed, size_t(256) << 20)))
            named.emplace(r.value("scene", std::string()), r.value("id", std::string()));
    } catch (const std::exception& e) {
        throw Error(listed.string() + ": " + e.what());
    }
    all.erase(std::remove_if(all.begin(), all.end(), [&](const CellResult& r) { return !named.count({r.scene, r.id}); }), all.end());
    return all;
}

namespace {
std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}
std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}
}  // namespace

std::string resultsCSV(const std::vector<CellResult>& results) {
    std::string s = "scene,technique,label,settings,status,ssim,score,rmse,psnr,brightness,leakFraction,leakEnergy,msTotal,msGI,passes,"
                    "memoryBytes,wallSeconds,paperScore,renderer,error,folder\n";
    for (const CellResult& r : results) {
        std::string passes;
        for (const auto& [name, ms] : r.passMs) passes += (passes.empty() ? "" : ";") + name + "=" + num(ms);
        std::vector<std::string> f = {r.scene, r.technique, r.label, joined(r.settings, ";"), r.status, num(r.ssim), num(r.score),
                                      num(r.rmse), num(r.psnr), num(r.brightness), num(r.leakFraction), num(r.leakEnergy),
                                      num(r.msTotal), num(r.msGI), passes, num(r.memoryBytes), num(r.wallSeconds),
                                      r.paperScore ? num(*r.paperScore) : "", r.renderer, r.error, r.folder};
        for (size_t i = 0; i < f.size(); ++i) s += (i ? "," : "") + csvField(f[i]);
        s += "\n";
    }
    return s;
}

json resultsJSON(const std::vector<CellResult>& results) {
    json a = json::array();
    for (const CellResult& r : results) a.push_back(resultToJson(r));
    return a;
}

double costOf(const CellResult& r, CostAxis axis) { return axis == CostAxis::GI ? r.msGI : r.msTotal; }

std::vector<size_t> paretoFront(const std::vector<CellResult>& results, CostAxis axis) {
    std::vector<size_t> ok;
    for (size_t i = 0; i < results.size(); ++i)
        if (results[i].ok()) ok.push_back(i);
    // Cheapest first (ties: the better picture, then the first); a cell joins the front when it
    // beats the best SSIM of every cheaper cell.
    std::stable_sort(ok.begin(), ok.end(), [&](size_t a, size_t b) {
        double ca = costOf(results[a], axis), cb = costOf(results[b], axis);
        if (ca != cb) return ca < cb;
        return results[a].ssim > results[b].ssim;
    });
    std::vector<size_t> front;
    double best = -INFINITY;
    for (size_t i : ok)
        if (results[i].ssim > best) {
            front.push_back(i);
            best = results[i].ssim;
        }
    return front;
}

namespace {
std::vector<double> ranks(const std::vector<double>& v) {
    std::vector<size_t> order(v.size());
    for (size_t i = 0; i < v.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
    std::vector<double> r(v.size());
    for (size_t i = 0; i < order.size();) {
        size_t j = i;
        while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
        for (size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * double(i + j) + 1.0;  // ties share their mean rank
        i = j + 1;
    }
    return r;
}
}  // namespace

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size() || a.size() < 2) return NAN;
    std::vector<double> ra = ranks(a), rb = ranks(b);
    double n = double(a.size()), ma = 0, mb = 0;
    for (size_t i = 0; i < a.size(); ++i) ma += ra[i] / n, mb += rb[i] / n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        sab += (ra[i] - ma) * (rb[i] - mb);
        saa += (ra[i] - ma) * (ra[i] - ma);
        sbb += (rb[i] - mb) * (rb[i] - mb);
    }
    return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : NAN;
}

}  // namespace gi::matrix
