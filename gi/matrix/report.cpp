#include "gi/matrix/report.h"

#include "gi/util/paths.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

namespace gi::matrix {

namespace {

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// A palette that stays apart for colour-blind readers (Okabe and Ito).
const char* colourOf(size_t i) {
    static const char* c[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442", "#000000"};
    return c[i % 8];
}

std::vector<std::string> techniquesOf(const std::vector<CellResult>& results) {
    std::vector<std::string> t;
    for (const CellResult& r : results)
        if (std::find(t.begin(), t.end(), r.technique) == t.end()) t.push_back(r.technique);
    return t;
}

std::string sceneSlug(const std::string& scene) { return "scene-" + slug(scene); }

const char* kStyle = R"(
body { font: 14px/1.4 system-ui, sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 2em; border-bottom: 1px solid #ccc; }
.top { display: flex; gap: 2em; align-items: flex-start; flex-wrap: wrap; }
figure { margin: 0; } figcaption { font-size: 0.85em; color: #555; }
table { border-collapse: collapse; margin-top: 1em; }
th, td { border: 1px solid #ddd; padding: 3px 6px; text-align: right; vertical-align: middle; }
td.text { text-align: left; max-width: 22em; overflow-wrap: anywhere; }
th { background: #f4f4f4; cursor: pointer; user-select: none; position: sticky; top: 0; }
th.sorted-asc::after { content: " \25B2"; } th.sorted-desc::after { content: " \25BC"; }
td img { width: 96px; image-rendering: pixelated; display: block; }
tr.best { background: #fff3c4; } tr.best td.label::before { content: "\2605 "; color: #b8860b; }
tr.failed { background: #fde2e2; } tr.front td.ms { font-weight: bold; }
.error { color: #a00; text-align: left; }
svg text { font: 11px system-ui, sans-serif; }
#load-check { margin-top: 2em; color: #555; }
)";

const char* kScript = R"(
function sortBy(th) {
  const table = th.closest('table'), body = table.tBodies[0];
  const col = Array.from(th.parentNode.children).indexOf(th);
  const numeric = th.dataset.type === 'num';
  const asc = !th.classList.contains('sorted-asc');
  table.querySelectorAll('th').forEach(h => h.classList.remove('sorted-asc', 'sorted-desc'));
  th.classList.add(asc ? 'sorted-asc' : 'sorted-desc');
  const key = r => { const c = r.children[col]; const v = c ? (c.dataset.v ?? c.textContent) : '';
                     return numeric ? (v === '' ? -Infinity : parseFloat(v)) : v.toLowerCase(); };
  const rows = Array.from(body.rows);
  rows.sort((a, b) => { const x = key(a), y = key(b); return (x < y ? -1 : x > y ? 1 : 0) * (asc ? 1 : -1); });
  rows.forEach(r => body.appendChild(r));
}
document.querySelectorAll('th').forEach(th => th.addEventListener('click', () => sortBy(th)));
window.addEventListener('load', () => {
  const imgs = Array.from(document.images);
  const loaded = imgs.filter(i => i.complete && i.naturalWidth > 0).length;
  document.body.dataset.imagesTotal = imgs.length;
  document.body.dataset.imagesLoaded = loaded;
  document.getElementById('load-check').textContent = loaded === imgs.length
    ? 'All ' + imgs.length + ' images loaded.'
    : (imgs.length - loaded) + ' of ' + imgs.length + ' images did not load (were the cell folders moved?).';
});
)";

}  // namespace

std::string paretoSVG(const std::vector<CellResult>& results, CostAxis axis) {
    auto cost = [axis](const CellResult& r) { return costOf(r, axis); };
    std::vector<size_t> ok;
    for (size_t i = 0; i < results.size(); ++i)
        if (results[i].ok()) ok.push_back(i);
    const double W = 540, H = 280, left = 54, right = 96, top = 12, bottom = 40;
    std::string s = "<svg class=\"pareto\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt("%.0f", W) + "\" height=\"" +
                    fmt("%.0f", H) + "\" viewBox=\"0 0 " + fmt("%.0f", W) + " " + fmt("%.0f", H) + "\">";
    s += "<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"white\"/>";
    if (ok.empty()) return s + "<text x=\"20\" y=\"40\">no cell finished</text></svg>";
    // The range of the positive costs; a cell that costs nothing (technique none's GI) sits at
    // the left edge.
    double msMin = INFINITY, msMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
    for (size_t i : ok)
        if (cost(results[i]) > 0.0) msMin = std::min(msMin, cost(results[i])), msMax = std::max(msMax, cost(results[i]));
    if (!std::isfinite(msMin)) msMin = msMax = 1.0;
    for (size_t i : ok) {
        yMin = std::min(yMin, results[i].ssim);
        yMax = std::max(yMax, results[i].ssim);
    }
    bool logX = msMax / msMin > 20.0;
    auto xf = [&](double ms) { return logX ? std::log10(std::max(ms, msMin)) : std::max(ms, 0.0); };
    double x0 = xf(msMin), x1 = xf(msMax);
    if (!logX && std::any_of(ok.begin(), ok.end(), [&](size_t i) { return cost(results[i]) <= 0.0; })) x0 = 0.0;
    if (x1 - x0 < 1e-9) x0 -= 0.5, x1 += 0.5;
    double padX = 0.05 * (x1 - x0);
    x0 -= padX, x1 += padX;
    if (yMax - yMin < 1e-4) yMin -= 0.005, yMax += 0.005;
    double padY = 0.08 * (yMax - yMin);
    yMin -= padY, yMax += padY;
    auto X = [&](double ms) { return left + (xf(ms) - x0) / (x1 - x0) * (W - left - right); };
    auto Y = [&](double v) { return top + (yMax - v) / (yMax - yMin) * (H - top - bottom); };
    // Axes and ticks.
    s += "<line x1=\"" + fmt("%.1f", left) + "\" y1=\"" + fmt("%.1f", H - bottom) + "\" x2=\"" + fmt("%.1f", W - right) + "\" y2=\"" +
         fmt("%.1f", H - bottom) + "\" stroke=\"#444\"/>";
    s += "<line x1=\"" + fmt("%.1f", left) + "\" y1=\"" + fmt("%.1f", top) + "\" x2=\"" + fmt("%.1f", left) + "\" y2=\"" +
         fmt("%.1f", H - bottom) + "\" stroke=\"#444\"/>";
    // The ms ticks start at 0 on a linear axis whose padding reaches below it (a cell that costs
    // nothing): no tick names a negative time.
    const double tick0 = logX ? x0 : std::max(x0, 0.0);
    for (int k = 0; k <= 4; ++k) {
        double v = yMin + (yMax - yMin) * k / 4.0;
        s += "<text x=\"" + fmt("%.1f", left - 4) + "\" y=\"" + fmt("%.1f", Y(v) + 4) + "\" text-anchor=\"end\">" + fmt("%.3f", v) + "</text>";
        double xv = tick0 + (x1 - tick0) * k / 4.0;
        double ms = logX ? std::pow(10.0, xv) : xv;
        s += "<text x=\"" + fmt("%.1f", X(ms)) + "\" y=\"" + fmt("%.1f", H - bottom + 14) + "\" text-anchor=\"middle\">" +
             fmt(ms < 10 ? "%.2f" : "%.0f", ms) + "</text>";
    }
    s += "<text x=\"" + fmt("%.1f", (left + W - right) / 2) + "\" y=\"" + fmt("%.1f", H - 6) + "\" text-anchor=\"middle\">" +
         std::string(axis == CostAxis::GI ? "ms of the GI passes" : "ms per frame") +
         std::string(logX ? " (log scale)" : "") + "</text>";
    s += "<text transform=\"translate(12 " + fmt("%.1f", (top + H - bottom) / 2) + ") rotate(-90)\" text-anchor=\"middle\">SSIM</text>";
    // The front as a staircase: from each front cell, right at its SSIM to the next one's ms.
    std::vector<size_t> front = paretoFront(results, axis);
    std::string path;
    for (size_t k = 0; k < front.size(); ++k) {
        const CellResult& r = results[front[k]];
        path += (k ? " L" : "M") + fmt("%.1f", X(cost(r))) + " " + fmt("%.1f", Y(r.ssim));
        double nextMs = k + 1 < front.size() ? cost(results[front[k + 1]]) : msMax;
        path += " L" + fmt("%.1f", X(nextMs)) + " " + fmt("%.1f", Y(r.ssim));
    }
    s += "<path class=\"front\" d=\"" + path + "\" fill=\"none\" stroke=\"#888\" stroke-dasharray=\"4 3\"/>";
    std::vector<std::string> techniques = techniquesOf(results);
    // Each technique's own front, thin in its colour.
    for (size_t t = 0; t < techniques.size(); ++t) {
        std::vector<CellResult> own;
        for (size_t i : ok)
            if (results[i].technique == techniques[t]) own.push_back(results[i]);
        std::vector<size_t> f = paretoFront(own, axis);
        if (f.size() < 2) continue;
        std::string line;
        for (size_t k = 0; k < f.size(); ++k) {
            line += (k ? " L" : "M") + fmt("%.1f", X(cost(own[f[k]]))) + " " + fmt("%.1f", Y(own[f[k]].ssim));
            if (k + 1 < f.size()) line += " L" + fmt("%.1f", X(cost(own[f[k + 1]]))) + " " + fmt("%.1f", Y(own[f[k]].ssim));
        }
        s += "<path class=\"technique-front\" d=\"" + line + "\" fill=\"none\" stroke=\"" + colourOf(t) + "\" stroke-width=\"1.2\"/>";
    }
    for (size_t i : ok) {
        const CellResult& r = results[i];
        size_t t = size_t(std::find(techniques.begin(), techniques.end(), r.technique) - techniques.begin());
        bool onFront = std::find(front.begin(), front.end(), i) != front.end();
        s += "<circle cx=\"" + fmt("%.1f", X(cost(r))) + "\" cy=\"" + fmt("%.1f", Y(r.ssim)) + "\" r=\"" + (onFront ? "5" : "3.5") +
             "\" fill=\"" + colourOf(t) + "\"" + (onFront ? " stroke=\"black\" stroke-width=\"1.5\"" : " fill-opacity=\"0.75\"") +
             "><title>" + escape(r.label) + ": SSIM " + fmt("%.4f", r.ssim) + ", " + fmt("%.1f", cost(r)) + " ms</title></circle>";
    }
    for (size_t t = 0; t < techniques.size(); ++t) {
        double y = top + 6 + 14.0 * double(t);
        s += "<circle cx=\"" + fmt("%.1f", W - right + 14) + "\" cy=\"" + fmt("%.1f", y) + "\" r=\"4\" fill=\"" + colourOf(t) + "\"/>";
        s += "<text x=\"" + fmt("%.1f", W - right + 22) + "\" y=\"" + fmt("%.1f", y + 4) + "\">" + escape(techniques[t]) + "</text>";
    }
    return s + "</svg>";
}

std::string reportHTML(const std::string& title, const std::vector<CellResult>& results) {
    size_t okCount = size_t(std::count_if(results.begin(), results.end(), [](const CellResult& r) { return r.ok(); }));
    std::set<std::string> renderers;
    for (const CellResult& r : results)
        if (!r.renderer.empty()) renderers.insert(r.renderer);
    bool paper = std::any_of(results.begin(), results.end(), [](const CellResult& r) { return r.paperScore.has_value(); });

    std::string h = "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + escape(title) +
                    " - GI Workbench matrix</title><style>" + kStyle + "</style></head>\n<body>\n";
    h += "<h1>" + escape(title) + "</h1>\n<p>" + std::to_string(results.size()) + " cells, " + std::to_string(okCount) + " rendered, " +
         std::to_string(results.size() - okCount) + " failed. SSIM is against each scene's path-traced reference (tone-mapped); " +
         "ms is the median frame after the first, its passes added up. Renderer: ";
    for (const std::string& r : renderers) h += escape(r) + "; ";
    h += "made by gi-matrix. Click a column to sort.</p>\n";

    std::vector<std::string> scenes;
    for (const CellResult& r : results)
        if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
    h += "<nav>";
    for (const std::string& s : scenes) h += "<a href=\"#" + sceneSlug(s) + "\">" + escape(s) + "</a> ";
    h += "</nav>\n";

    for (const std::string& scene : scenes) {
        std::vector<CellResult> cells;
        for (const CellResult& r : results)
            if (r.scene == scene) cells.push_back(r);
        std::stable_sort(cells.begin(), cells.end(), [](const CellResult& a, const CellResult& b) {
            if (a.ok() != b.ok()) return a.ok();
            return a.ssim > b.ssim;
        });
        // The best cell of each technique, and the front.
        std::map<std::string, size_t> best;
        for (size_t i = 0; i < cells.size(); ++i)
            if (cells[i].ok() && (!best.count(cells[i].technique) || cells[i].ssim > cells[best[cells[i].technique]].ssim))
                best[cells[i].technique] = i;
        std::vector<size_t> front = paretoFront(cells);

        h += "<section class=\"scene\" id=\"" + sceneSlug(scene) + "\"><h2>" + escape(scene) + "</h2>\n<div class=\"top\">";
        for (const CellResult& c : cells)
            if (c.ok()) {
                h += "<figure><img class=\"reference\" src=\"" + escape(c.folder) + "/reference.png\" alt=\"reference\" width=\"256\">" +
                     "<figcaption>path-traced reference</figcaption></figure>";
                break;
            }
        h += "<figure>" + paretoSVG(cells, CostAxis::GI) + "<figcaption>SSIM against the GI passes' own ms (the technique's passes)" +
             "</figcaption></figure>";
        h += "<figure>" + paretoSVG(cells) + "<figcaption>SSIM against the frame's ms; the Pareto front (no cell is better for less) is ringed" +
             "; each technique's own front is the line in its colour</figcaption></figure>";
        h += "<div class=\"front-list\"><b>Pareto front</b><ol>";
        for (size_t i : front)
            h += "<li>" + escape(cells[i].label) + ": SSIM " + fmt("%.4f", cells[i].ssim) + ", " + fmt("%.1f", cells[i].msTotal) + " ms</li>";
        h += "</ol>";
        // Each technique's own front, when it has more than one point.
        for (const std::string& t : techniquesOf(cells)) {
            std::vector<CellResult> own;
            for (const CellResult& c : cells)
                if (c.technique == t) own.push_back(c);
            std::vector<size_t> f = paretoFront(own);
            if (f.size() < 2) continue;
            h += "<p class=\"technique-front\"><b>" + escape(t) + " front:</b> ";
            for (size_t k = 0; k < f.size(); ++k)
                h += (k ? "; " : "") + escape(own[f[k]].label) + " (" + fmt("%.4f", own[f[k]].ssim) + ", " + fmt("%.0f", own[f[k]].msTotal) + " ms)";
            h += "</p>";
        }
        std::vector<double> ours, theirs;
        for (const CellResult& c : cells)
            if (c.ok() && c.paperScore) ours.push_back(c.ssim), theirs.push_back(*c.paperScore);
        if (ours.size() >= 3)
            h += "<p class=\"rank\">Rank correlation (Spearman) of our SSIM with the paper's score over " + std::to_string(ours.size()) +
                 " cells: <b>" + fmt("%.2f", spearman(ours, theirs)) + "</b> (1: the same order, 0: unrelated, -1: reversed)</p>";
        h += "</div></div>\n<table class=\"cells\"><thead><tr><th>image</th><th>heat</th><th>leak</th><th>technique</th>"
             "<th>label</th><th>settings</th><th data-type=\"num\">SSIM</th><th data-type=\"num\">score</th>";
        if (paper) h += "<th data-type=\"num\">paper score</th>";
        h += "<th data-type=\"num\">RMSE</th><th data-type=\"num\">PSNR</th><th data-type=\"num\">brightness</th>"
             "<th data-type=\"num\">leak</th><th data-type=\"num\">ms</th><th data-type=\"num\">GI ms</th><th>passes</th><th data-type=\"num\">MiB</th>"
             "<th data-type=\"num\">wall s</th></tr></thead><tbody>\n";
        for (size_t i = 0; i < cells.size(); ++i) {
            const CellResult& c = cells[i];
            std::vector<std::string> cls{"cell"};
            auto b = best.find(c.technique);
            if (b != best.end() && b->second == i) cls.push_back("best");
            if (!c.ok()) cls.push_back("failed");
            if (std::find(front.begin(), front.end(), i) != front.end()) cls.push_back("front");
            std::string classes;
            for (const std::string& x : cls) classes += (classes.empty() ? "" : " ") + x;
            h += "<tr class=\"" + classes + "\" data-id=\"" + escape(c.id) + "\">";
            if (c.ok()) {
                for (const char* img : {"image.png", "heat_map.png", "leak_map.png"})
                    h += "<td><a href=\"" + escape(c.folder) + "/" + img + "\"><img src=\"" + escape(c.folder) + "/" + img + "\" alt=\"" +
                         img + "\" loading=\"eager\"></a></td>";
            } else {
                h += "<td colspan=\"3\" class=\"error\">" + escape(c.status) + ": " + escape(c.error) + "</td>";
            }
            std::string settings;
            for (const std::string& s : c.settings) settings += (settings.empty() ? "" : "<br>") + escape(s);
            h += "<td class=\"text\">" + escape(c.technique) + "</td><td class=\"text label\">" + escape(c.label) + "</td><td class=\"text\">" +
                 settings + "</td>";
            auto numCell = [&](double v, const char* f, const char* extra = "") {
                return c.ok() ? "<td class=\"" + std::string(extra) + "\" data-v=\"" + fmt("%.9g", v) + "\">" + fmt(f, v) + "</td>"
                              : std::string("<td data-v=\"\"></td>");
            };
            h += numCell(c.ssim, "%.4f") + numCell(c.score, "%.3g");
            if (paper) h += c.paperScore ? "<td data-v=\"" + fmt("%.9g", *c.paperScore) + "\">" + fmt("%.3f", *c.paperScore) + "</td>" : "<td data-v=\"\"></td>";
            h += numCell(c.rmse, "%.4f") + numCell(c.psnr, "%.2f") + numCell(c.brightness, "%.3f") + numCell(c.leakFraction, "%.4f") +
                 numCell(c.msTotal, "%.1f", "ms") + numCell(c.msGI, "%.1f");
            // The passes folded, the costliest named on the fold.
            std::string passes;
            if (!c.passMs.empty()) {
                auto top = std::max_element(c.passMs.begin(), c.passMs.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
                passes = "<details><summary>" + escape(top->first) + " " + fmt("%.1f", top->second) + "</summary>";
                for (const auto& [name, ms] : c.passMs) passes += escape(name) + " " + fmt("%.1f", ms) + "<br>";
                passes += "</details>";
            }
            h += "<td class=\"text\">" + passes + "</td>" + numCell(c.memoryBytes / 1048576.0, "%.1f") +
                 "<td data-v=\"" + fmt("%.9g", c.wallSeconds) + "\">" + fmt("%.1f", c.wallSeconds) + "</td></tr>\n";
        }
        h += "</tbody></table></section>\n";
    }
    h += "<p id=\"load-check\">Checking the images...</p>\n<script>" + std::string(kScript) + "</script>\n</body></html>\n";
    return h;
}

void writeResults(const std::filesystem::path& dir, const std::string& title, const std::vector<CellResult>& results) {
    writeFileAtomic(dir / "results.csv", resultsCSV(results));
    writeFileAtomic(dir / "results.json", resultsJSON(results).dump(2) + "\n");
    writeFileAtomic(dir / "index.html", reportHTML(title, results));
}

}  // namespace gi::matrix
