// Cone tracing through the voxel levels (seed 000 section 1, seed 003 section 1), shared by the
// screen trace (trace.comp) and the voxel bounce (bounce.comp).
//
// A cone with half-angle tan `tanHalf` starts `nudge` voxel diagonals from the apex, divided by
// n.w without face sides (seed 000 eq. 3.4; n.w is clamped at 0.25 so grazing cones do not start
// far away; vctConeStart in vct_shared.h says why face sides leave the division out), then
// marches: diameter d = max(2 tanHalf t, voxel), sample at lod = log2(d / voxel) - kVCTFootprintLod
// (below), composite front to back (C += (1 - a) c, a += (1 - a) a_s), advance by
// stepMultiplier * d. A step longer than the sample's texel thickens its opacity to
// 1 - (1 - a)^k (k = step / texel), and a shorter one thins it, so the result does not depend on
// the step much.
//
// Why not lod = log2(d / voxel), the texel as wide as the cone: a trilinear sample reaches one
// texel either side of its point, and a surface sits up to half a texel from the centre of the
// texel that holds it, so such a sample takes in surfaces up to 1.5 d away, three times the cone's
// radius. With 60-degree cones that reaches behind the apex at every step: the receiver's own
// floor darkened every cone (a floor under a panel lit from below gathers 43 % of the analytic
// value at the default nudge 3 that way; 89 % at 1.25). Sampling kVCTFootprintLod finer shrinks the reach to
// the cone's own radius at log2(3) = 1.58; 1.25 is what the shift-invariance test allows (the
// sweep is in vct_shared.h). The march ends at
// maxDistance, at opacity 0.99, or when a sample's footprint lies wholly outside the coarsest level.
//
// Levels (cascaded and clipmap modes): level k has voxels 2^k times level 0's. A sample uses the
// finest level that holds it (with half a coarse voxel of margin), at lod log2(d / voxel_k),
// blended towards the next level over the outer tenth of the level, as the LPV cascades do.
//
// Variants (defines the host injects): VCT_LEVELS radiance volumes, VCT_ANISO six directional
// volumes, VCT_SH three SH volumes. Each program declares only the samplers it uses: on Mesa
// 22 llvmpipe a compute shader with more than 16 samplers reads garbage from the later ones,
// silently.
#include "vct/common.glsl"

#ifndef VCT_SIDES
#define VCT_SIDES 0
#endif
#ifndef VCT_LEVELS
#define VCT_LEVELS 1
#endif
layout(binding = kVCTUnitRadiance) uniform sampler3D uRadiance[VCT_LEVELS];
#if VCT_ANISO
layout(binding = kVCTUnitAniso) uniform sampler3D uAniso;  // +X -X +Y -Y +Z -Z side by side along x
#if VCT_SIDES
layout(binding = kVCTUnitCoverageOctants) uniform sampler3D uCoverageOctants;  // the facing coverage by octant (octants.comp)
layout(binding = kVCTUnitCentroid) uniform sampler3D uCentroid;  // mean position of the voxels' content (resolve.comp)
#endif
#endif
#if VCT_SH
layout(binding = kVCTUnitSH) uniform sampler3D uSHR;
layout(binding = kVCTUnitSH + 1) uniform sampler3D uSHG;
layout(binding = kVCTUnitSH + 2) uniform sampler3D uSHB;
#endif

// Work counted for the screen trace's report (trace.comp sums them; bounce.comp leaves them
// unread): cone steps taken and texture calls made, by this invocation.
uint gVCTSamples = 0u, gVCTFetches = 0u;
// The cone being marched: its apex and the receiver's normal there (traceCone sets them).
vec3 gVCTApex = vec3(0.0), gVCTApexNormal = vec3(0.0, 1.0, 0.0);

vec3 levelCoord(int k, vec3 p) {
    return (p - uVCT.levelMinCell[k].xyz) / (uVCT.levelMinCell[k].w * float(uVCT.resolution)) +
           vec3(uVCT.levelWrap[k].xyz) / float(uVCT.resolution);
}

vec4 levelRadiance(int k, vec3 tc, float lod) {
    gVCTFetches += 1u;
#if VCT_LEVELS == 1
    return textureLod(uRadiance[0], tc, lod);
#else
    vec4 r = vec4(0.0);
    for (int i = 0; i < VCT_LEVELS; ++i)
        if (i == k) r = textureLod(uRadiance[i], tc, lod);
    return r;
#endif
}

#if VCT_ANISO
// The atlas at lod for a cone marching along dir: the slab of each axis's sign (slab index
// 2 axis + (dir < 0)) weighted dir^2, one fetch filtered across the two mips around lod (mip 0 is
// level 0, so lod 0 to 1 needs no read beside the atlas). x is kept half a texel of the coarser
// mip read inside the slab, so the filter does not blend in the neighbouring direction, and the
// fade to the zero border that y and z get from the sampler is applied to x by hand (a point u
// texels inside a face keeps 0.5 + u of the face texel), blended between the two mips. Exact away
// from the x faces; within a texel of them the finer mip is read at the coarser one's clamp
// (reading each mip at its own clamp took two fetches per direction and cost the trace 1.8x).
// With face sides, mip 0 holds each voxel's sides facing back along the slab's direction, with
// their coverage beside it (mip.comp), so a side no fragment faces adds nothing: the dark face of
// a thin wall stays dark even from a grazing direction.
vec4 sampleAniso(vec3 tc, float lod, vec3 dir) {
    vec3 w = dir * dir;
    vec3 slab = vec3(0.0, 2.0, 4.0) + step(dir, vec3(0.0));
    float f = fract(lod);
    float size = float(uVCT.resolution) * exp2(-floor(lod));  // the finer mip's texels per slab
    float halfTexel = (f > 0.0 ? 1.0 : 0.5) / size;
    float x = clamp(tc.x, halfTexel, 1.0 - halfTexel);
    float edge = min(tc.x, 1.0 - tc.x) * size;
    float fade = mix(clamp(edge + 0.5, 0.0, 1.0), clamp(0.5 * edge + 0.5, 0.0, 1.0), f);
    // Only the slabs of the axes the direction has a component along, in x, y, z order: a loop
    // whose trip count is that number, since llvmpipe leaves a loop once every invocation it runs
    // together has (cones of neighbouring pixels on one wall share their zero components), where
    // a zero-weight read in a sum or a branch is still executed, masked.
    int axes = (w.x > 0.0 ? 1 : 0) | (w.y > 0.0 ? 2 : 0) | (w.z > 0.0 ? 4 : 0);
    int count = bitCount(axes);
    gVCTFetches += uint(VCT_SIDES != 0 ? count + 1 : count);
    vec4 r = vec4(0.0);
    for (int k = 0; k < count; ++k) {
        int a = findLSB(axes);
        axes &= axes - 1;
        r += w[a] * textureLod(uAniso, vec3((x + slab[a]) / 6.0, tc.yz), lod);
    }
    r *= fade;
#if VCT_SIDES
    // The mean radiance of the surfaces facing the cone, times the opacity: the coverage of its
    // three directions' slabs (mip.comp) in one call, from its octant's slab (octants.comp; an
    // axis of zero weight adds nothing whichever sign it takes).
    int octant = int(dir.x <= 0.0) | (int(dir.y <= 0.0) << 1) | (int(dir.z <= 0.0) << 2);
    float coverage = fade * dot(w, textureLod(uCoverageOctants, vec3((x + float(octant)) / 8.0, tc.yz), lod).rgb);
    return vec4(coverage > 1e-6 ? r.rgb / coverage * r.a : vec3(0.0), r.a);
#else
    return r;  // without face sides the coverage is the opacity, so r is the premultiplied radiance
#endif
}
#endif

// Premultiplied radiance towards the apex and opacity of level k at p, for a cone marching along dir.
vec4 sampleLevel(int k, vec3 p, float lod, vec3 dir) {
    vec3 tc = levelCoord(k, p);
    lod = clamp(lod, 0.0, uVCT.maxLod);
#if VCT_SH
    vec4 b = shBasis(-dir);
    float a = levelRadiance(0, tc, lod).a;
    gVCTFetches += 3u;
    vec3 c = vec3(dot(textureLod(uSHR, tc, lod), b), dot(textureLod(uSHG, tc, lod), b), dot(textureLod(uSHB, tc, lod), b));
    return vec4(max(c, vec3(0.0)), a);
#elif VCT_ANISO
    // One atlas call per direction for every lod: a CPU rasterizer runs both sides of a branch
    // whose condition may differ between the invocations it executes together (masked, not
    // skipped), so a separate read for lod < 1 (level 0's own volume, or a second atlas call)
    // costs every sample, taken or not.
#if VCT_SIDES
    // Face sides: which face of a surface the cone sees depends on where the surface lies from
    // the apex, not on the cone's axis. A 60-degree cone along the floor, or slightly up,
    // takes in the floor below it in its footprint; by the axis's signs it read the floor's
    // unlit underside, opaque and black, where the path tracer sees the lit top. So the sample
    // reads its texel's content as seen from the apex, along the direction to the content's
    // centroid (the centroid volume's mips, resolve.comp), and drops the content that lies in
    // the receiver's own plane (less than kVCTOwnPlaneStart voxels above it): a plane cannot
    // occlude or light a cone that leaves it.
    vec4 content = textureLod(uCentroid, tc, lod);
    gVCTFetches += 1u;
    vec3 view = dir;
    float keep = 1.0;
    if (content.a > 1e-4) {
        float voxel = uVCT.levelMinCell[0].w;
        vec3 toContent = uVCT.levelMinCell[0].xyz + content.xyz / content.a * voxel - gVCTApex;
        keep = clamp((dot(toContent, gVCTApexNormal) / voxel - kVCTOwnPlaneStart) / kVCTOwnPlaneRamp, 0.0, 1.0);
        float length2 = dot(toContent, toContent);
        if (length2 > 1e-12) view = toContent * inversesqrt(length2);
    }
    return keep * sampleAniso(tc, lod, view);
#else
    return sampleAniso(tc, lod, dir);
#endif
#else
    return levelRadiance(k, tc, lod);
#endif
}

// Level k's sample at p for a cone of this diameter (kVCTFootprintLod finer than it), its opacity
// made that of a path `step` long: a sample stands for its texel, 2^lod voxels of level k (lod as
// sampleLevel clamps it), and a longer step thickens it to 1 - (1 - a)^(step / texel).
vec4 sampleFootprint(int k, vec3 p, float diameter, float step, vec3 dir) {
    float voxel = uVCT.levelMinCell[k].w;
    float lod = clamp(log2(max(diameter / voxel, 1.0)) - kVCTFootprintLod, 0.0, uVCT.maxLod);
    vec4 s = sampleLevel(k, p, lod, dir);
    float ratio = step / (voxel * exp2(lod));
    if (ratio != 1.0 && s.a > 0.0) {
        float a = 1.0 - pow(max(1.0 - s.a, 0.0), ratio);
        s = vec4(s.rgb * (a / s.a), a);
    }
    return s;
}

// The sample of the finest level that holds p, blended towards the next level over the outer
// tenth of its extent. False outside every level.
bool sampleVoxels(vec3 p, float diameter, float step, vec3 dir, out vec4 s) {
    for (int k = 0; k < uVCT.levelCount; ++k) {
        float extent = uVCT.levelMinCell[k].w * float(uVCT.resolution);
        vec3 d = abs(p - (uVCT.levelMinCell[k].xyz + 0.5 * extent)) - 0.5 * extent;
        float m = max(d.x, max(d.y, d.z));
        // The outermost level also takes samples centred outside it whose footprint reaches in:
        // with steps of a diameter, the sample that would reach a far wall is often centred past it.
        if (m > (k + 1 == uVCT.levelCount ? 0.5 * diameter : 0.0)) continue;
        s = sampleFootprint(k, p, diameter, step, dir);
        float band = kVCTLevelBlend * extent;
        float e = clamp((m + band) / band, 0.0, 1.0);
        if (e > 0.0 && k + 1 < uVCT.levelCount) s = mix(s, sampleFootprint(k + 1, p, diameter, step, dir), e);
        return true;
    }
    s = vec4(0.0);
    return false;
}

// Marches one cone; `occlusion` receives the opacity gathered within occlusionDistance.
// `phase`, in [0, 1), is where along the cone the samples fall (kVCTPhaseUnstaggered: where they
// always had): the start is scaled by r^(phase - 0.5), r = 1 + 2 stepMultiplier tanHalf being the
// ratio of one sample's distance to the previous one's once the cone is wider than a voxel, so
// the samples of the march move by up to half a step either way along it, the same fraction of a
// step at every step. With face sides the screen trace takes it from its pixel by a 2 x 2 pattern
// (trace.comp) that the upsampling filter averages out (upsample.comp). Unstaggered, every pixel
// of a wall along an axis sampled the voxels at the same phase, so what a view gathered depended
// on where the scene fell in the grid: the shift test
// (VCTGL.IndirectLightDoesNotDependOnWhereTheSceneFallsInTheGrid, face sides, the tail, three
// bounces) +3.5 / +6.2 / +5.3 % -> +2.5 / +3.3 / +2.8 %, and a floor under a panel 74-109 % of
// the analytic light as the nudge went 0-4 -> 90 % at each. The unstaggered phase was a lucky one
// in two tests, which now see the average of four: the sky through a closed box's walls
// (VCTGL.ConesThatEndUnoccludedSeeTheSky) and the two-room leak. Without face sides the screen
// trace stays unstaggered: the cones that start nearer the floor lose its light to
// self-occlusion (87 -> 78 % of the panel's light at the default nudge). The voxel bounce does
// too: staggering it by voxel did not help there (at 0.5 voxel, +3.7 against +3.9 %).
const float kVCTPhaseUnstaggered = 0.5;
vec4 traceCone(vec3 apex, vec3 n, vec3 dir, float tanHalf, float maxDistance, float occlusionDistance, float phase,
               out float occlusion) {
    float voxel = uVCT.levelMinCell[0].w;
    gVCTApex = apex;
    gVCTApexNormal = n;
    float t = vctConeStart(uVCT.nudge, voxel, dot(n, dir), VCT_SIDES != 0) * pow(1.0 + 2.0 * uVCT.stepMultiplier * tanHalf, phase - 0.5);
    vec4 acc = vec4(0.0);
    occlusion = 0.0;
    for (int i = 0; i < kVCTMaxConeSteps && t < maxDistance && acc.a < kVCTOpaque; ++i) {
        float diameter = max(2.0 * tanHalf * t, voxel);
        float step = uVCT.stepMultiplier * diameter;
        vec4 s;
        if (!sampleVoxels(apex + dir * t, diameter, step, dir, s)) break;
        gVCTSamples += 1u;
        acc += (1.0 - acc.a) * s;
        if (t < occlusionDistance) occlusion = acc.a;
        t += step;
    }
    return acc;
}

// A tangent frame around n (Frisvad's, with Duff et al.'s fix for n.z < 0).
mat3 tangentFrame(vec3 n) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float b = n.x * n.y * a;
    vec3 t = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
    return mat3(t, bt, n);
}
