#include "gi/matrix/tune.h"

#include "gi/preset/preset.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace gi::matrix {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string numberText(double v, bool integer) {
    if (integer) return std::to_string(int64_t(std::llround(v)));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

// The value of a dotted key ("lpv.gridResolution") in presetToJson's nesting, or null.
json valueAt(const json& base, const std::string& key) {
    const json* j = &base;
    size_t from = 0;
    while (j->is_object()) {
        size_t dot = key.find('.', from);
        auto it = j->find(key.substr(from, dot == std::string::npos ? std::string::npos : dot - from));
        if (it == j->end()) return nullptr;
        j = &*it;
        if (dot == std::string::npos) return *j;
        from = dot + 1;
    }
    return nullptr;
}

}  // namespace

std::vector<TuneParameter> tuneSpace(const std::string& technique, const json& base) {
    std::vector<TuneParameter> space;
    std::string prefix = technique + ".";
    for (const SettingInfo& s : listSettings()) {
        if (s.key.rfind(prefix, 0) != 0 || s.developer) continue;
        TuneParameter p;
        p.key = s.key;
        json current = valueAt(base, s.key);
        // Numbers of any JSON kind (integer or float) count as the same type.
        bool sameKind = current.is_number() ? s.defaultValue.is_number() : current.type() == s.defaultValue.type();
        if (current.is_null() || !sameKind) current = s.defaultValue;
        if (s.type == "bool") {
            p.values = {"false", "true"};
            p.start = current.get<bool>() ? 1 : 0;
            p.ordered = false;
        } else if (s.type == "enum") {
            p.values = s.choices;
            auto it = std::find(p.values.begin(), p.values.end(), current.get<std::string>());
            p.start = it == p.values.end() ? 0 : size_t(it - p.values.begin());
            p.ordered = false;
        } else if (s.type == "int" || s.type == "float") {
            bool integer = s.type == "int";
            double d = current.get<double>();
            std::vector<double> v;
            if (integer && s.max - s.min <= 8) {
                for (double x = s.min; x <= s.max; ++x) v.push_back(x);
            } else if (d > 0.0) {
                const double factors[] = {0.25, 0.5, 0.7071, 1.0, 1.4142, 2.0, 4.0};
                for (double f : factors) {
                    double x = d * f;
                    if (integer) {
                        if (f != 0.7071 && f != 1.4142) v.push_back(std::round(x));  // powers of two only
                    } else {
                        v.push_back(x);
                    }
                }
                for (double& x : v) x = std::clamp(x, s.min, s.max);
            } else {
                continue;  // 0 means "automatic" (maxDistance, levelExtent): left to the technique
            }
            std::sort(v.begin(), v.end());
            v.erase(std::unique(v.begin(), v.end()), v.end());
            for (double x : v) p.values.push_back(numberText(x, integer));
            p.start = size_t(std::min_element(v.begin(), v.end(), [&](double a, double b) { return std::abs(a - d) < std::abs(b - d); }) -
                             v.begin());
        } else {
            continue;  // strings, vectors, lists
        }
        if (p.values.size() >= 2) space.push_back(std::move(p));
    }
    return space;
}

bool tuneBetter(const CellResult& a, const CellResult& b, double budgetMs) {
    if (!a.ok()) return false;
    if (!b.ok()) return true;
    bool fa = a.msTotal <= budgetMs, fb = b.msTotal <= budgetMs;
    if (fa != fb) return fa;
    if (fa) return a.ssim > b.ssim + (a.msTotal > b.msTotal ? kTuneCostlyGain : kTuneGain);
    return a.msTotal < b.msTotal;
}

namespace {

// Renders points of the space as matrix cells, each point once.
class Evaluator {
public:
    Evaluator(const MatrixSpec& spec, const TuneOptions& options, std::vector<TuneParameter> space, std::string method)
        : mSpec(spec), mOptions(options), mSpace(std::move(space)) {
        mReport.method = std::move(method);
    }

    std::vector<size_t> defaults() const {
        std::vector<size_t> p;
        for (const TuneParameter& t : mSpace) p.push_back(t.start);
        return p;
    }
    const std::vector<TuneParameter>& space() const { return mSpace; }
    bool exhausted() const {
        return mReport.renders >= mOptions.maxRenders || (mOptions.run.cancel && mOptions.run.cancel->load());
    }

    std::vector<std::string> settingsOf(const std::vector<size_t>& point) const {
        std::vector<std::string> s;
        for (size_t i = 0; i < mSpace.size(); ++i)
            if (point[i] != mSpace[i].start) s.push_back(mSpace[i].key + "=" + mSpace[i].values[point[i]]);
        return s;
    }

    const CellResult& evaluate(const std::vector<size_t>& point, const std::string& change) {
        std::vector<std::string> settings = settingsOf(point);
        std::string key;
        for (const std::string& s : settings) key += s + "\n";
        auto found = mSeen.find(key);
        if (found != mSeen.end()) return found->second;
        std::string label = mOptions.technique;
        for (const std::string& s : settings) label += " " + s;
        Cell cell = makeCell(mSpec, 0, mOptions.technique, label, settings);
        TuneStep step;
        step.settings = settings;
        step.change = change;
        fs::path done = cellFolder(mOptions.run.outDir, cell) / "result.json";
        std::error_code ec;
        if (mOptions.run.resume && fs::is_regular_file(done, ec)) {
            try {
                step.result = resultFromJson(json::parse(readTextFile(done, size_t(16) << 20)), done.string());
            } catch (const std::exception&) {
                step.result = CellResult();
            }
        }
        // A point read from an earlier run counts as a render all the same, so a resumed search
        // takes the path it would have taken uninterrupted, and searches that share an output
        // folder (a comparison on the same measurements) spend their renders alike.
        // A render that ran out of time under a limit at least as long as this one's would
        // again: it is reused too (other failures render again, as a matrix's --resume does).
        step.reused = step.result.ok() ||
                      (step.result.status == "timeout" && step.result.wallSeconds + 0.5 >= mSpec.timeoutSeconds);
        if (step.reused)
            ++mReport.reused;
        else
            step.result = mOptions.render ? mOptions.render(mSpec, cell, mOptions.run) : runCell(mSpec, cell, mOptions.run);
        step.render = ++mReport.renders;
        step.withinBudget = step.result.ok() && step.result.msTotal <= mOptions.budgetMs;
        if (!mReport.best || tuneBetter(step.result, mReport.best->result, mOptions.budgetMs)) {
            step.best = true;
            mReport.best = step;
        }
        mReport.steps.push_back(step);
        if (mOptions.progress) mOptions.progress(mReport);
        return mSeen.emplace(key, step.result).first->second;
    }

    TuneReport report() && { return std::move(mReport); }

private:
    const MatrixSpec& mSpec;
    const TuneOptions& mOptions;
    std::vector<TuneParameter> mSpace;
    std::map<std::string, CellResult> mSeen;
    TuneReport mReport;
};

std::string changeText(const TuneParameter& p, size_t from, size_t to) { return p.key + " " + p.values[from] + " -> " + p.values[to]; }

}  // namespace

TuneReport tunePatternSearch(const MatrixSpec& spec, const TuneOptions& options) {
    Evaluator e(spec, options, tuneSpace(options.technique, options.base), "pattern search");
    std::vector<size_t> current = e.defaults();
    CellResult best = e.evaluate(current, "defaults");
    const auto& space = e.space();
    for (bool improved = true; improved && !e.exhausted();) {
        improved = false;
        for (size_t i = 0; i < space.size() && !e.exhausted(); ++i) {
            const TuneParameter& p = space[i];
            if (p.ordered) {
                // Walk one way while it keeps improving; try the other way only if the first did
                // not. Up first (a finer grid, more steps: usually a better picture), but down
                // first while the best is over the budget (usually cheaper).
                const bool over = !(best.ok() && best.msTotal <= options.budgetMs);
                for (int dir : {over ? -1 : +1, over ? +1 : -1}) {
                    bool moved = false;
                    while (!e.exhausted()) {
                        long next = long(current[i]) + dir;
                        if (next < 0 || next >= long(p.values.size())) break;
                        std::vector<size_t> candidate = current;
                        candidate[i] = size_t(next);
                        const CellResult& r = e.evaluate(candidate, changeText(p, current[i], candidate[i]));
                        if (!tuneBetter(r, best, options.budgetMs)) break;
                        best = r;
                        current = candidate;
                        moved = improved = true;
                    }
                    if (moved) break;
                }
            } else {
                size_t from = current[i];
                for (size_t v = 0; v < p.values.size() && !e.exhausted(); ++v) {
                    if (v == from) continue;
                    std::vector<size_t> candidate = current;
                    candidate[i] = v;
                    const CellResult& r = e.evaluate(candidate, changeText(p, from, v));
                    if (tuneBetter(r, best, options.budgetMs)) {
                        best = r;
                        current = candidate;
                        improved = true;
                    }
                }
            }
        }
    }
    return std::move(e).report();
}

TuneReport tuneGrid(const MatrixSpec& spec, const TuneOptions& options) {
    Evaluator e(spec, options, tuneSpace(options.technique, options.base), "grid");
    const auto& space = e.space();
    // Lowest, default and highest of the first k ladders, 3^k within the renders.
    size_t k = 0, count = 1;
    std::vector<std::vector<size_t>> levels;
    for (size_t i = 0; i < space.size(); ++i) {
        std::vector<size_t> l = {0, space[i].start, space[i].values.size() - 1};
        std::sort(l.begin(), l.end());
        l.erase(std::unique(l.begin(), l.end()), l.end());
        if (count * l.size() > options.maxRenders) break;
        count *= l.size();
        levels.push_back(l);
        ++k;
    }
    std::vector<size_t> digits(k, 0);
    for (size_t n = 0; n < count && !e.exhausted(); ++n) {
        std::vector<size_t> point = e.defaults();
        std::string change;
        for (size_t i = 0; i < k; ++i) {
            point[i] = levels[i][digits[i]];
            change += (i ? ", " : "") + space[i].key + "=" + space[i].values[point[i]];
        }
        e.evaluate(point, change.empty() ? "defaults" : change);
        for (size_t i = 0; i < k; ++i) {
            if (++digits[i] < levels[i].size()) break;
            digits[i] = 0;
        }
    }
    return std::move(e).report();
}

json tuneReportToJson(const TuneReport& r, double budgetMs) {
    json steps = json::array();
    for (const TuneStep& s : r.steps)
        steps.push_back({{"render", s.render},
                         {"reused", s.reused},
                         {"change", s.change},
                         {"settings", s.settings},
                         {"status", s.result.status},
                         {"ssim", s.result.ssim},
                         {"ms", s.result.msTotal},
                         {"withinBudget", s.withinBudget},
                         {"best", s.best}});
    json j = {{"method", r.method}, {"budgetMs", budgetMs}, {"renders", r.renders}, {"reused", r.reused}, {"steps", steps}};
    if (r.best)
        j["best"] = {{"settings", r.best->settings}, {"ssim", r.best->result.ssim}, {"ms", r.best->result.msTotal},
                     {"withinBudget", r.best->withinBudget}};
    return j;
}

}  // namespace gi::matrix
