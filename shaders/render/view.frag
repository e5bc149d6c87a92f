// Debug views of any texture: channel select, exposure, zoom and pan, depth linearisation and
// cube maps unfolded as a cross or shown as a latlong (equirectangular) image, at any mip. Used
// by the editor's buffer previewer and Roughness mips panel, and `gi-render --views`.
#include "render/render_shared.h"
#include "common/sh.h"
#include "common/color.glsl"

layout(binding = kUnitSource) uniform sampler2D uSource;
layout(binding = kUnitSourceCube) uniform samplerCube uSourceCube;
layout(binding = kUnitSource3D) uniform sampler3D uVolumeR;
layout(binding = kUnitSource3D + 1) uniform sampler3D uVolumeG;
layout(binding = kUnitSource3D + 2) uniform sampler3D uVolumeB;
layout(binding = kUnitSourceU3D) uniform usampler3D uVolumeU;
in vec2 vUV;
out vec4 oColor;


vec3 cubeCross(vec2 uv, out bool inside) {
    // 4 x 3 cross, uv.y = 0 at the top: row 1 holds -X +Z +X -Z; +Y above +Z, -Y below, each
    // face meeting +Z along a shared edge.
    vec2 cell = floor(uv * vec2(4.0, 3.0));
    vec2 f = fract(uv * vec2(4.0, 3.0)) * 2.0 - 1.0;
    inside = true;
    if (cell.y == 1.0) {
        if (cell.x == 0.0) return vec3(-1.0, -f.y, f.x);
        if (cell.x == 1.0) return vec3(f.x, -f.y, 1.0);
        if (cell.x == 2.0) return vec3(1.0, -f.y, -f.x);
        return vec3(-f.x, -f.y, -1.0);
    }
    // uv.y (and f.y) grow downwards: cell row 0 is the top one.
    if (cell.x == 1.0 && cell.y == 0.0) return vec3(f.x, 1.0, f.y);
    if (cell.x == 1.0 && cell.y == 2.0) return vec3(f.x, -1.0, -f.y);
    inside = false;
    return vec3(0.0, 0.0, 1.0);
}

// The direction at latlong coordinates (v = 0 at the top): the inverse of latLongUV in
// gi/envmap/envmap_image.h (u = 0.5 + atan2(d.x, -d.z) / 2 pi, v = acos(d.y) / pi), unrotated.
vec3 latLongDirection(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * kPi, theta = uv.y * kPi;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// A blue-green-yellow-red ramp for magnitudes in [0, 1].
vec3 falseColour(float x) {
    x = clamp(x, 0.0, 1.0);
    return clamp(vec3(1.5 - abs(4.0 * x - 3.0), 1.5 - abs(4.0 * x - 2.0), 1.5 - abs(4.0 * x - 1.0)), 0.0, 1.0);
}

vec3 volumeCoord(vec2 uv) {
    if (uRender.axis == 0) return vec3(uRender.slice, uv.y, uv.x);
    if (uRender.axis == 2) return vec3(uv, uRender.slice);
    return vec3(uv.x, uRender.slice, uv.y);
}

void main() {
    vec2 uv = (vUV - 0.5) / uRender.zoom + 0.5 + uRender.pan;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        float checker = mod(floor(gl_FragCoord.x / 8.0) + floor(gl_FragCoord.y / 8.0), 2.0);
        oColor = vec4(vec3(0.1 + 0.05 * checker), 1.0);
        return;
    }
    vec4 v;
    if (uRender.mode >= kViewVoxelColor && uRender.mode <= kViewVoxelPackedNormal) {
        // Voxel volumes: the nearest voxel of mip `level`, so single voxels stay visible.
        vec3 p = volumeCoord(uv);
        vec3 c;
        if (uRender.mode >= kViewVoxelPacked) {
            ivec3 size = textureSize(uVolumeU, 0);
            uint packedValue = texelFetch(uVolumeU, clamp(ivec3(p * vec3(size)), ivec3(0), size - 1), 0).r;
            c = unpackUnorm4x8(packedValue).rgb;
            if (uRender.mode == kViewVoxelPacked) c = linearToSRGB(c * uRender.exposureScale);
        } else {
            int level = int(uRender.level);
            ivec3 size = textureSize(uVolumeR, level);
            vec4 s = texelFetch(uVolumeR, clamp(ivec3(p * vec3(size)), ivec3(0), size - 1), level);
            c = uRender.mode == kViewVoxelAlpha ? vec3(s.a) : linearToSRGB(s.rgb * uRender.exposureScale);
            if (uRender.falseColour != 0) c = falseColour(uRender.mode == kViewVoxelAlpha ? s.a : max(s.r, max(s.g, s.b)) * uRender.exposureScale);
        }
        oColor = vec4(c, 1.0);
        return;
    }
    if (uRender.mode == kViewSHVolume || uRender.mode == kViewVolume) {
        vec3 p = volumeCoord(uv);
        vec3 c;
        if (uRender.mode == kViewSHVolume) {
            vec4 r = texture(uVolumeR, p), g = texture(uVolumeG, p), b = texture(uVolumeB, p);
            if (uRender.shComponent >= 0) c = vec3(r[uRender.shComponent], g[uRender.shComponent], b[uRender.shComponent]) * uRender.scale;
            // Irradiance on a surface facing `direction`: light travelling against it.
            else c = max(vec3(dot(r, shCosLobe(-uRender.direction.xyz)), dot(g, shCosLobe(-uRender.direction.xyz)), dot(b, shCosLobe(-uRender.direction.xyz))), 0.0) * uRender.scale / kPi;
        } else {
            vec4 gv = texture(uVolumeR, p);
            c = vec3(uRender.shComponent >= 0 ? gv[uRender.shComponent] : clamp(shEval(gv, -uRender.direction.xyz), 0.0, 1.0));
        }
        c *= uRender.exposureScale;
        float m = max(c.r, max(c.g, c.b));
        oColor = vec4(uRender.falseColour != 0 ? falseColour(m) : linearToSRGB(c), 1.0);
        return;
    }
    if (uRender.mode == kViewCubeCross || uRender.mode == kViewCubeLatLong) {
        vec3 dir;
        if (uRender.mode == kViewCubeCross) {
            bool inside;
            dir = cubeCross(vec2(uv.x, 1.0 - uv.y), inside);
            if (!inside) {
                oColor = vec4(0.05, 0.05, 0.05, 1.0);
                return;
            }
        } else {
            dir = latLongDirection(vec2(uv.x, 1.0 - uv.y));
        }
        v = textureLod(uSourceCube, dir, uRender.level);
        if (uRender.depthCube != 0) v = vec4(v.rrr, 1.0);
    } else {
        v = textureLod(uSource, uv, uRender.level);
    }
    vec3 c;
    bool single = dot(uRender.channelMask, vec4(1.0)) < 1.5;
    if (uRender.mode == kViewNormal) {
        c = v.xyz * 0.5 + 0.5;
    } else if (uRender.mode == kViewPosition) {
        c = v.w > 0.0 ? fract(v.xyz) : vec3(0.0);
    } else if (uRender.mode == kViewLinearDepth) {
        float linear = viewDepthOf(v.r, uRender.depthNear, uRender.depthFar);
        c = vec3(1.0 - clamp(linear / uRender.range, 0.0, 1.0));
    } else if (uRender.mode == kViewRawDepth) {
        c = vec3(v.r);
    } else {
        c = v.rgb;
    }
    if (single) c = vec3(dot(v, uRender.channelMask));
    if (uRender.mode == kViewColor || uRender.mode == kViewCubeCross || uRender.mode == kViewCubeLatLong) c = linearToSRGB(c * uRender.exposureScale);
    else if (uRender.mode == kViewDisplay) c = clamp(c * uRender.exposureScale, 0.0, 1.0);
    oColor = vec4(c, 1.0);
}
