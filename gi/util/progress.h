// Progress of long work (the environment prefilter, the path-traced reference): the core reports
// through a sink the caller hands it, and never prints; gi-render's sink prints to stderr, the
// editor may show a bar. A report comes after each step; the sink decides how often to show one.
#pragma once

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

namespace gi {

struct ProgressUpdate {
    std::string task;       // what runs, e.g. "environment prefilter", "reference"
    double done = 0.0;      // steps finished ...
    double total = 0.0;     // ... of this many
    std::string unit;       // what a step is, e.g. "spp", "mips"
    double fraction = 0.0;  // of the work done, in [0, 1] (steps may differ in size), for the time left
    double seconds = 0.0;   // since the work began
    std::string detail;     // optional, e.g. "mip 1, 1024^2"
};

using ProgressSink = std::function<void(const ProgressUpdate&)>;

// "64 / 1024 spp, 12.3 s, ~3 min left" (the time left from the fraction done; none at the end).
inline std::string formatProgress(const ProgressUpdate& p) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f / %.0f ", p.done, p.total);
    std::string s = p.task + ": " + buf + p.unit;
    if (!p.detail.empty()) s += " (" + p.detail + ")";
    std::snprintf(buf, sizeof buf, ", %.1f s", p.seconds);
    s += buf;
    if (p.fraction > 0.0 && p.fraction < 1.0) {
        double left = p.seconds * (1.0 - p.fraction) / p.fraction;
        if (left < 90.0)
            std::snprintf(buf, sizeof buf, ", ~%.0f s left", std::ceil(left));
        else if (left < 5400.0)
            std::snprintf(buf, sizeof buf, ", ~%.0f min left", std::round(left / 60.0));
        else
            std::snprintf(buf, sizeof buf, ", ~%.1f h left", left / 3600.0);
        s += buf;
    }
    return s;
}

}  // namespace gi
