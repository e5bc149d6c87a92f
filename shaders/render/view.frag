// Debug views of any texture: channel select, exposure, zoom and pan, depth linearisation and
// cube maps unfolded as a cross or shown as a latlong (equirectangular) image, at any mip. Used
// by the editor's buffer previewer and Roughness mips panel, and `gi-render --views`.
#include "common/shared.h"
#include "common/sh.h"
#include "common/color.glsl"

layout(binding = kUnitSource) uniform sampler2D uSource;
layout(binding = kUnitSourceCube) uniform samplerCube uSourceCube;
layout(binding = kUnitSource3D) uniform sampler3D uVolumeR;
layout(binding = kUnitSource3D + 1) uniform sampler3D uVolumeG;
layout(binding = kUnitSource3D + 2) uniform sampler3D uVolumeB;
layout(binding = kUnitSourceU3D) uniform usampler3D uVolumeU;
uniform int uAxis;           // volume views: slice normal axis
uniform float uSlice;        // volume views: slice position 0..1
uniform int uSHComponent;    // -1: irradiance / blocking towards uDirection; else that coefficient
uniform vec3 uDirection;
uniform bool uFalseColour;
uniform float uScale;        // stored value to radiance
uniform int uMode;
uniform vec4 uChannelMask;   // (1,1,1,0) shows RGB; a single 1 shows that channel as grey
uniform float uExposureScale;
uniform float uNear;
uniform float uFar;
uniform float uRange;       // distance shown as black in linear depth views
uniform vec2 uPan;           // texture-space offset of the view centre
uniform float uZoom;         // 1 shows the whole texture
uniform float uLevel;        // mip level
uniform bool uDepthCube;     // cube views: a depth cube (point shadow map) shows its one channel as grey

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
    if (uAxis == 0) return vec3(uSlice, uv.y, uv.x);
    if (uAxis == 2) return vec3(uv, uSlice);
    return vec3(uv.x, uSlice, uv.y);
}

void main() {
    vec2 uv = (vUV - 0.5) / uZoom + 0.5 + uPan;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        float checker = mod(floor(gl_FragCoord.x / 8.0) + floor(gl_FragCoord.y / 8.0), 2.0);
        oColor = vec4(vec3(0.1 + 0.05 * checker), 1.0);
        return;
    }
    vec4 v;
    if (uMode >= kViewVoxelColor && uMode <= kViewVoxelPackedNormal) {
        // Voxel volumes: the nearest voxel of mip `level`, so single voxels stay visible.
        vec3 p = volumeCoord(uv);
        vec3 c;
        if (uMode >= kViewVoxelPacked) {
            ivec3 size = textureSize(uVolumeU, 0);
            uint packedValue = texelFetch(uVolumeU, clamp(ivec3(p * vec3(size)), ivec3(0), size - 1), 0).r;
            c = unpackUnorm4x8(packedValue).rgb;
            if (uMode == kViewVoxelPacked) c = linearToSRGB(c * uExposureScale);
        } else {
            int level = int(uLevel);
            ivec3 size = textureSize(uVolumeR, level);
            vec4 s = texelFetch(uVolumeR, clamp(ivec3(p * vec3(size)), ivec3(0), size - 1), level);
            c = uMode == kViewVoxelAlpha ? vec3(s.a) : linearToSRGB(s.rgb * uExposureScale);
            if (uFalseColour) c = falseColour(uMode == kViewVoxelAlpha ? s.a : max(s.r, max(s.g, s.b)) * uExposureScale);
        }
        oColor = vec4(c, 1.0);
        return;
    }
    if (uMode == kViewSHVolume || uMode == kViewVolume) {
        vec3 p = volumeCoord(uv);
        vec3 c;
        if (uMode == kViewSHVolume) {
            vec4 r = texture(uVolumeR, p), g = texture(uVolumeG, p), b = texture(uVolumeB, p);
            if (uSHComponent >= 0) c = vec3(r[uSHComponent], g[uSHComponent], b[uSHComponent]) * uScale;
            // Irradiance on a surface facing uDirection: light travelling along -uDirection.
            else c = max(vec3(dot(r, shCosLobe(-uDirection)), dot(g, shCosLobe(-uDirection)), dot(b, shCosLobe(-uDirection))), 0.0) * uScale / kPi;
        } else {
            vec4 gv = texture(uVolumeR, p);
            c = vec3(uSHComponent >= 0 ? gv[uSHComponent] : clamp(shEval(gv, -uDirection), 0.0, 1.0));
        }
        c *= uExposureScale;
        float m = max(c.r, max(c.g, c.b));
        oColor = vec4(uFalseColour ? falseColour(m) : linearToSRGB(c), 1.0);
        return;
    }
    if (uMode == kViewCubeCross || uMode == kViewCubeLatLong) {
        vec3 dir;
        if (uMode == kViewCubeCross) {
            bool inside;
            dir = cubeCross(vec2(uv.x, 1.0 - uv.y), inside);
            if (!inside) {
                oColor = vec4(0.05, 0.05, 0.05, 1.0);
                return;
            }
        } else {
            dir = latLongDirection(vec2(uv.x, 1.0 - uv.y));
        }
        v = textureLod(uSourceCube, dir, uLevel);
        if (uDepthCube) v = vec4(v.rrr, 1.0);
    } else {
        v = textureLod(uSource, uv, uLevel);
    }
    vec3 c;
    bool single = dot(uChannelMask, vec4(1.0)) < 1.5;
    if (uMode == kViewNormal) {
        c = v.xyz * 0.5 + 0.5;
    } else if (uMode == kViewPosition) {
        c = v.w > 0.0 ? fract(v.xyz) : vec3(0.0);
    } else if (uMode == kViewLinearDepth) {
        float z = v.r * 2.0 - 1.0;
        float linear = 2.0 * uNear * uFar / (uFar + uNear - z * (uFar - uNear));
        c = vec3(1.0 - clamp(linear / uRange, 0.0, 1.0));
    } else if (uMode == kViewRawDepth) {
        c = vec3(v.r);
    } else {
        c = v.rgb;
    }
    if (single) c = vec3(dot(v, uChannelMask));
    if (uMode == kViewColor || uMode == kViewCubeCross || uMode == kViewCubeLatLong) c = linearToSRGB(c * uExposureScale);
    else if (uMode == kViewDisplay) c = clamp(c * uExposureScale, 0.0, 1.0);
    oColor = vec4(c, 1.0);
}
