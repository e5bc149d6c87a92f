#include "gi/render/strokes.h"

#include "gi/util/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gi {

namespace {

void blend(std::vector<uint8_t>& rgba, int width, int height, int x, int y, const glm::vec4& c, float coverage) {
    if (x < 0 || y < 0 || x >= width || y >= height || coverage <= 0.0f) return;
    uint8_t* p = &rgba[(size_t(y) * width + x) * 4];
    float a = c.a * std::min(coverage, 1.0f);
    for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::lround(float(p[k]) * (1.0f - a) + 255.0f * c[k] * a));
}

float segmentDistance(const glm::vec2& p, const glm::vec2& a, const glm::vec2& b) {
    glm::vec2 ab = b - a;
    float len2 = glm::dot(ab, ab);
    float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (a + t * ab));
}

// The pixels within `pad` of the box lo..hi, clamped to the image as floats first (a point far
// outside, e.g. projected from near a camera plane, must not overflow an int).
struct PixelBox {
    glm::ivec2 lo, hi;
    bool empty() const { return hi.x < lo.x || hi.y < lo.y; }
};
PixelBox pixelBox(glm::vec2 lo, glm::vec2 hi, float pad, int width, int height) {
    glm::vec2 top(float(width - 1), float(height - 1));
    return {glm::ivec2(glm::clamp(glm::floor(lo - pad), glm::vec2(0.0f), top)),
            glm::ivec2(glm::clamp(glm::ceil(hi + pad), glm::vec2(0.0f), top))};
}

// Distances of the box's pixel centres to the nearest of the segments, each segment visiting
// only the pixels within `reach` of it; the rest stay at infinity.
struct DistanceField {
    PixelBox box;
    int w = 0;
    std::vector<float> d;
    DistanceField(const PixelBox& b) : box(b), w(b.hi.x - b.lo.x + 1) {
        d.assign(size_t(w) * size_t(b.hi.y - b.lo.y + 1), std::numeric_limits<float>::infinity());
    }
    void add(const glm::vec2& a, const glm::vec2& b, float reach, int width, int height) {
        PixelBox s = pixelBox(glm::min(a, b), glm::max(a, b), reach, width, height);
        s.lo = glm::max(s.lo, box.lo);
        s.hi = glm::min(s.hi, box.hi);
        for (int y = s.lo.y; y <= s.hi.y; ++y)
            for (int x = s.lo.x; x <= s.hi.x; ++x) {
                float& out = at(x, y);
                out = std::min(out, segmentDistance(glm::vec2(float(x) + 0.5f, float(y) + 0.5f), a, b));
            }
    }
    float& at(int x, int y) { return d[size_t(y - box.lo.y) * size_t(w) + size_t(x - box.lo.x)]; }
};

glm::vec2 minOf(const std::vector<glm::vec2>& points) {
    glm::vec2 m = points.front();
    for (const glm::vec2& p : points) m = glm::min(m, p);
    return m;
}
glm::vec2 maxOf(const std::vector<glm::vec2>& points) {
    glm::vec2 m = points.front();
    for (const glm::vec2& p : points) m = glm::max(m, p);
    return m;
}

}  // namespace

void drawStrokes(std::vector<uint8_t>& rgba, int width, int height, const std::vector<Stroke>& strokes) {
    GI_ASSERT(rgba.size() >= size_t(width) * height * 4, "drawStrokes: image too small");
    if (width <= 0 || height <= 0) return;
    for (const Stroke& s : strokes) {
        float r = 0.5f * s.width;
        PixelBox box = pixelBox(glm::min(s.a, s.b), glm::max(s.a, s.b), r + 1.0f, width, height);
        for (int y = box.lo.y; y <= box.hi.y; ++y)
            for (int x = box.lo.x; x <= box.hi.x; ++x) {
                float d = segmentDistance(glm::vec2(float(x) + 0.5f, float(y) + 0.5f), s.a, s.b);
                blend(rgba, width, height, x, y, s.colour, r + 0.5f - d);
            }
    }
}

void drawPolyline(std::vector<uint8_t>& rgba, int width, int height, const std::vector<glm::vec2>& points, bool closed,
                  const glm::vec4& colour, float strokeWidth) {
    GI_ASSERT(rgba.size() >= size_t(width) * height * 4, "drawPolyline: image too small");
    if (width <= 0 || height <= 0 || points.empty()) return;
    float r = 0.5f * strokeWidth;
    DistanceField field(pixelBox(minOf(points), maxOf(points), r + 1.0f, width, height));
    size_t n = points.size();
    size_t segments = n == 1 ? 1 : closed ? n : n - 1;
    for (size_t i = 0; i < segments; ++i) field.add(points[i], points[(i + 1) % n], r + 1.0f, width, height);
    for (int y = field.box.lo.y; y <= field.box.hi.y; ++y)
        for (int x = field.box.lo.x; x <= field.box.hi.x; ++x) blend(rgba, width, height, x, y, colour, r + 0.5f - field.at(x, y));
}

void fillPolygon(std::vector<uint8_t>& rgba, int width, int height, const std::vector<glm::vec2>& points,
                 const glm::vec4& colour) {
    GI_ASSERT(rgba.size() >= size_t(width) * height * 4, "fillPolygon: image too small");
    if (width <= 0 || height <= 0 || points.size() < 3) return;
    // The soft edge needs each pixel's distance to the outline only within one pixel of it.
    DistanceField field(pixelBox(minOf(points), maxOf(points), 1.0f, width, height));
    size_t n = points.size();
    for (size_t i = 0; i < n; ++i) field.add(points[i], points[(i + 1) % n], 1.0f, width, height);
    std::vector<float> crossings;
    for (int y = field.box.lo.y; y <= field.box.hi.y; ++y) {
        float yc = float(y) + 0.5f;
        crossings.clear();
        for (size_t i = 0; i < n; ++i) {
            const glm::vec2 &a = points[i], &b = points[(i + 1) % n];
            if ((a.y <= yc) != (b.y <= yc)) crossings.push_back(a.x + (yc - a.y) / (b.y - a.y) * (b.x - a.x));
        }
        std::sort(crossings.begin(), crossings.end());
        size_t left = 0;  // crossings left of the pixel centre
        for (int x = field.box.lo.x; x <= field.box.hi.x; ++x) {
            float xc = float(x) + 0.5f;
            while (left < crossings.size() && crossings[left] < xc) ++left;
            float d = field.at(x, y);
            blend(rgba, width, height, x, y, colour, left % 2 == 1 ? 0.5f + d : 0.5f - d);
        }
    }
}

void drawGlyphLines(std::vector<uint8_t>& rgba, int width, int height, const glm::mat4& viewProj,
                    const std::vector<GlyphLine>& lines) {
    GI_ASSERT(rgba.size() >= size_t(width) * height * 4, "drawGlyphLines: image too small");
    // Pixel coordinates with y up (row 0 at the bottom, as the image is stored).
    auto project = [&](const glm::vec3& p, glm::vec2& out) {
        glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
        if (c.w <= 1e-4f) return false;
        out = (glm::vec2(c) / c.w * 0.5f + 0.5f) * glm::vec2(width, height);
        return true;
    };
    std::vector<Stroke> strokes;
    strokes.reserve(lines.size());
    for (const GlyphLine& l : lines) {
        Stroke s;
        if (!project(l.a, s.a) || !project(l.b, s.b)) continue;
        s.colour = l.colour;
        s.width = l.width;
        strokes.push_back(s);
    }
    drawStrokes(rgba, width, height, strokes);
}

std::vector<Stroke> segmentText(const std::string& text, float x, float y, float height, const glm::vec4& colour) {
    // Segments a (top) b c d e f g (middle), and which of them each digit lights.
    static const char* lit[10] = {"abcdef", "bc", "abged", "abgcd", "fgbc", "afgcd", "afgedc", "abc", "abcdefg", "abcdfg"};
    const float w = 0.5f * height, m = 0.5f * height, thickness = std::max(1.5f, height / 7.0f);
    std::vector<Stroke> strokes;
    for (char ch : text) {
        if (ch == '.') {
            strokes.push_back({{x + 0.5f * thickness, y}, {x + 0.5f * thickness, y}, colour, thickness * 1.2f});
            x += 2.0f * thickness;
            continue;
        }
        if (ch < '0' || ch > '9') {
            x += w + 2.0f * thickness;
            continue;
        }
        for (const char* seg = lit[ch - '0']; *seg; ++seg) {
            glm::vec2 a, b;
            switch (*seg) {
                case 'a': a = {0, height}, b = {w, height}; break;
                case 'b': a = {w, height}, b = {w, m}; break;
                case 'c': a = {w, m}, b = {w, 0}; break;
                case 'd': a = {0, 0}, b = {w, 0}; break;
                case 'e': a = {0, 0}, b = {0, m}; break;
                case 'f': a = {0, m}, b = {0, height}; break;
                default: a = {0, m}, b = {w, m}; break;
            }
            strokes.push_back({glm::vec2(x, y) + a, glm::vec2(x, y) + b, colour, thickness});
        }
        x += w + 2.0f * thickness;
    }
    return strokes;
}

}  // namespace gi
