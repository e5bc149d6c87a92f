#include "gi/preset/reflect.h"

#include <cctype>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>

namespace gi {

std::string readableKey(std::string_view key) {
    auto isUpper = [](char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; };
    auto isLowerOrDigit = [](char c) { return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)); };
    std::string out;
    const size_t n = key.size();
    for (size_t i = 0; i < n; ++i) {
        const char c = key[i];
        const bool upper = isUpper(c);
        const bool prevLower = i > 0 && isLowerOrDigit(key[i - 1]);
        const bool prevUpper = i > 0 && isUpper(key[i - 1]);
        const bool nextLower = i + 1 < n && std::islower(static_cast<unsigned char>(key[i + 1]));
        // A word starts at a capital after a lower-case letter, or at the last capital of an
        // acronym that a lower-case word follows ("SHOrder" -> "SH order").
        if (upper && i > 0 && (prevLower || (prevUpper && nextLower))) out += ' ';
        // The capital that starts a lower-case word is lowered; acronyms ("MB", "Y") stay.
        out += upper && nextLower ? char(std::tolower(static_cast<unsigned char>(c))) : c;
    }
    return out;
}

const char* costName(Cost c) {
    switch (c) {
        case Cost::Uniform: return "uniform";
        case Cost::Reallocate: return "reallocate";
        case Cost::Recompile: return "recompile";
        case Cost::ReloadScene: return "reload scene";
    }
    return "mixed";
}

namespace detail {

double shortestDouble(float f) {
    char text[32];
    auto [end, ec] = std::to_chars(text, text + sizeof text - 1, f);  // shortest text that reads back to f
    if (ec != std::errc()) return double(f);
    *end = '\0';
    return std::strtod(text, nullptr);
}

size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        cur[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            bool same = std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

std::string nearest(std::string_view key, const std::vector<std::string>& candidates) {
    std::string best;
    size_t bestDistance = SIZE_MAX;
    for (const auto& c : candidates) {
        size_t d = editDistance(key, c);
        if (d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    return best;
}

std::string formatNumber(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string rangeText(const FieldMeta& m) {
    auto end = [](double v) { return std::isinf(v) ? std::string(v < 0 ? "-inf" : "inf") : formatNumber(v); };
    return "[" + end(m.min) + ", " + end(m.max) + "]";
}

std::string where(const std::string& context, const std::string& key) {
    return context + ": key '" + key + "'";
}

}  // namespace detail
}  // namespace gi
