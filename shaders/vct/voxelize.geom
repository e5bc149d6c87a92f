// Voxelization, geometry stage (seed 000 section 1, after Crassin and Green): each triangle is
// projected orthographically along its dominant axis (largest |n.axis|) onto a grid-sized
// viewport, one pixel per voxel column, and grown for conservative rasterization: every edge
// moves out by the distance to the farthest corner of a pixel (0.5 (|n.x| + |n.y|)), and the
// new corners are the intersections of the moved edges. Sharp corners then reach far out, so the
// fragment stage discards fragments outside the triangle's bounding box grown by half a pixel.
// Attributes at the moved corners are extrapolated with the original triangle's barycentrics.
// The seed's listing has bugs here (digest 000 section 6); this is written from the description.
// Slicing (uVCT.sliceAxis > 0, seed 001): the triangle is projected along the axis given, as it
// is, and a triangle edge-on to it is dropped (the other two axes catch it).
#include "vct/vct_shared.h"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 vWorld[];
in vec3 vNormal[];
in vec2 vUV[];
in vec4 vTangent[];
in vec2 vUV1[];

out vec3 gGrid;     // grid coordinates in voxels, swizzled: xy on the viewport, z the depth
out vec3 gNormal;
out vec2 gUV;
out vec4 gTangent;
out vec2 gUV1;
flat out vec4 gBox;     // xy min, zw max of the grown bounding box in pixels
flat out vec2 gDepthRange;  // the triangle's depth range in voxels
flat out int gAxis;     // 0: x dominant, 1: y, 2: z

vec3 swizzle(vec3 g, int axis) { return axis == 0 ? g.yzx : axis == 1 ? g.zxy : g; }

void main() {
    vec3 g[3];
    for (int i = 0; i < 3; ++i) g[i] = (vWorld[i] - uVCT.gridMin.xyz) / uVCT.cellSize;
    vec3 n = abs(cross(g[1] - g[0], g[2] - g[0]));
    int axis = n.x >= n.y && n.x >= n.z ? 0 : (n.y >= n.z ? 1 : 2);
    bool slicing = uVCT.sliceAxis > 0;
    if (slicing) axis = uVCT.sliceAxis - 1;
    vec3 s[3];
    for (int i = 0; i < 3; ++i) s[i] = swizzle(g[i], axis);

    vec2 p0 = s[0].xy, p1 = s[1].xy, p2 = s[2].xy;
    float area = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
    if (abs(area) < 1e-12) return;  // degenerate in projection (and so in 3D along every axis)
    float orient = area > 0.0 ? 1.0 : -1.0;

    // Outward edge normals and offsets; edge i runs from vertex i to vertex i + 1.
    vec2 en[3];
    float ed[3];
    for (int i = 0; i < 3; ++i) {
        vec2 e = s[(i + 1) % 3].xy - s[i].xy;
        en[i] = normalize(vec2(e.y, -e.x)) * orient;
        ed[i] = slicing ? 0.0 : 0.5 * (abs(en[i].x) + abs(en[i].y));
    }
    float grow = slicing ? 0.0 : 0.5;
    vec2 lo = min(p0, min(p1, p2)) - grow, hi = max(p0, max(p1, p2)) + grow;
    float zlo = min(s[0].z, min(s[1].z, s[2].z)), zhi = max(s[0].z, max(s[1].z, s[2].z));

    for (int i = 0; i < 3; ++i) {
        // Vertex i joins edge i - 1 (incoming) and edge i (outgoing).
        int a = (i + 2) % 3;
        vec2 na = en[a], nb = en[i];
        float det = na.x * nb.y - na.y * nb.x;
        vec2 off;
        if (abs(det) < 1e-4) off = na * ed[a];
        else off = vec2(ed[a] * nb.y - ed[i] * na.y, na.x * ed[i] - nb.x * ed[a]) / det;
        vec2 q = s[i].xy + off;
        // Barycentrics of q in the projected triangle, to extrapolate the attributes.
        vec2 v0 = p1 - p0, v1 = p2 - p0, v2 = q - p0;
        float b1 = (v2.x * v1.y - v1.x * v2.y) / (v0.x * v1.y - v1.x * v0.y);
        float b2 = (v0.x * v2.y - v2.x * v0.y) / (v0.x * v1.y - v1.x * v0.y);
        float b0 = 1.0 - b1 - b2;
        gGrid = vec3(q, b0 * s[0].z + b1 * s[1].z + b2 * s[2].z);
        gNormal = b0 * vNormal[0] + b1 * vNormal[1] + b2 * vNormal[2];
        gUV = b0 * vUV[0] + b1 * vUV[1] + b2 * vUV[2];
        gTangent = b0 * vTangent[0] + b1 * vTangent[1] + b2 * vTangent[2];
        gUV1 = b0 * vUV1[0] + b1 * vUV1[1] + b2 * vUV1[2];
        gBox = vec4(lo, hi);
        gDepthRange = vec2(zlo, zhi);
        gAxis = axis;
        gl_Position = vec4(q / float(uVCT.resolution) * 2.0 - 1.0, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
