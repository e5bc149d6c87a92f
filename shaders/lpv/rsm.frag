// Reflective shadow map texel: world position (w: the surfel's world area), normal facing the
// light, diffuse albedo (the geometry volume's, for bounces), and the light the surfel reflects
// diffusely per unit of its area (its radiant exitance, albedo * irradiance): the flux it reflects,
// albedo * light * projected texel area (directional) or albedo * intensity * texel solid angle
// (spot, and each face of a point light's cube), over its world area. Injection multiplies it back
// by the area in 32-bit floats: an exitance fits a half float at any scene scale, a flux does not
// (it scales with the square of the units: a Cornell box 2 cm wide underflowed to black). The intensity towards the texel
// is the light model's, color * lightProfile(l, dist, cosAxis), whatever the light's kind. The
// light is entry lightIndex of the frame's light buffer.
// ALPHA_CUT 0: the variant for Opaque materials, without discard (render/gbuffer.frag says why).
#ifndef ALPHA_CUT
#define ALPHA_CUT 1
#endif
#include "common/light.h"
#include "common/material.glsl"
#include "lpv/lpv_shared.h"

in vec3 vWorld;
in vec3 vNormal;
in vec2 vUV;
in vec4 vTangent;
in vec2 vUV1;

layout(location = 0) out vec4 oFlux;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oPosition;
layout(location = 3) out vec4 oAlbedo;  // diffuse albedo, for the geometry volume's bounces

void main() {
    // The material as the G-buffer reads it (common/material.glsl): base colour, cut-outs,
    // metallic and the normal-mapped normal.
    vec4 base = materialBaseColor(vUV, vUV1);
    vec3 n = materialNormal(vNormal, vTangent, gl_FrontFacing, vUV, vUV1);
    float metallic = materialRoughnessMetallic(vUV, vUV1).y;
#if ALPHA_CUT
    if (materialCut(base.a)) discard;
#endif
    GPULight l = uLights[uLPV.lightIndex];
    vec3 L;  // towards the light
    vec3 flux;
    float area;
    if (l.info.x == kLightDirectional) {
        L = -l.direction.xyz;
        flux = l.color.rgb * uLPV.texelArea;
        area = uLPV.texelArea;
    } else {
        vec3 toLight = l.position.xyz - vWorld;
        float d = length(toLight);
        L = toLight / d;
        // A texel's solid angle shrinks with cos^3 of its angle off the map's axis (dA cos^3 / 1):
        // the spot's axis, or a cube face's, whose cosine is the largest component of |L| since
        // a face sees exactly the directions along which its axis dominates.
        float cosAxis = dot(-L, l.direction.xyz);
        float cosMap = uLPV.cubeFace != 0 ? max(abs(L.x), max(abs(L.y), abs(L.z))) : cosAxis;
        float solidAngle = uLPV.texelSolidAngle * cosMap * cosMap * cosMap;
        flux = l.color.rgb * lightProfile(l, d, cosAxis) * solidAngle;
        area = solidAngle * d * d;
    }
    if (dot(n, L) < 0.0) n = -n;  // two-sided, as the raster and the path tracer
    float cosTheta = max(dot(n, L), kLPVMinRSMCosine);
    oFlux = vec4(base.rgb * (1.0 - metallic) * flux * (cosTheta / area), 1.0);
    oAlbedo = vec4(base.rgb * (1.0 - metallic), 1.0);
    oNormal = vec4(n, 1.0);
    oPosition = vec4(vWorld, area / cosTheta);
}
