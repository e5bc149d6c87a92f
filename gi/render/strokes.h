// Anti-aliased 2D strokes and fills drawn on the CPU into an RGBA8 image, for the previewer images
// the runner writes (VCT's cone glyphs, the volumetric phase plot) where there is no ImGui.
//
// Coordinates are pixels with y up: (0, 0) is the bottom-left corner of the bottom row, the order
// GL reads back and gi::writePNG expects; pixel (x, y) has its centre at (x + 0.5, y + 0.5).
// Coverage comes from the distance d of a pixel centre to the stroke's centre line: 1 within half
// the width, falling linearly to 0 over one pixel. Colours are straight RGBA in 0..1, already
// display-encoded; a pixel is blended once per draw call as c * a + old * (1 - a) (alpha stays).
//   - drawStrokes blends each segment on its own, so where two translucent segments overlap
//     (the joins of a chain) the colour is laid twice;
//   - drawPolyline blends its whole chain once, by the distance to the nearest segment, so a
//     translucent curve has even joins;
//   - fillPolygon fills by the even-odd rule with the same one-pixel soft edge.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace gi {

// A segment from a to b in pixels (y up); a == b is a dot of diameter `width`.
struct Stroke {
    glm::vec2 a{0.0f}, b{0.0f};
    glm::vec4 colour{1.0f};  // straight RGBA, 0..1 (display-encoded)
    float width = 1.0f;      // pixels
};

// Each stroke alpha-blended over the image in turn.
void drawStrokes(std::vector<uint8_t>& rgba, int width, int height, const std::vector<Stroke>& strokes);

// The chain through `points` (closed: back to the first) as one stroke.
void drawPolyline(std::vector<uint8_t>& rgba, int width, int height, const std::vector<glm::vec2>& points, bool closed,
                  const glm::vec4& colour, float strokeWidth);

// The polygon through `points` (even-odd rule), blended once.
void fillPolygon(std::vector<uint8_t>& rgba, int width, int height, const std::vector<glm::vec2>& points,
                 const glm::vec4& colour);

// A world-space stroke of a previewer overlay (cone glyphs, cascade boxes); a == b is a dot of diameter `width` pixels.
struct GlyphLine {
    glm::vec3 a{0.0f}, b{0.0f};
    glm::vec4 colour{1.0f};  // straight RGBA, 0..1 (display-encoded)
    float width = 1.0f;      // pixels
};

// Draws the strokes over an RGBA8 image (bottom row first, as GL reads it back) seen through
// viewProj; alpha-blended, strokes behind the camera skipped. The projected strokes are drawn by
// gi/render/strokes.h's drawStrokes.
void drawGlyphLines(std::vector<uint8_t>& rgba, int width, int height, const glm::mat4& viewProj,
                    const std::vector<GlyphLine>& lines);

// `text` (digits and '.') as seven-segment strokes, its bottom-left corner at (x, y), y up: labels
// of the previewer images (no font is at hand without ImGui).
std::vector<Stroke> segmentText(const std::string& text, float x, float y, float height, const glm::vec4& colour);

}  // namespace gi
