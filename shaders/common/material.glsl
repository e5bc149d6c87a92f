// Material textures are read through sampleMaterial(). Mesa 22.3 llvmpipe's anisotropic filter,
// with implicit derivatives, stalls for minutes per draw when a pixel's footprint spans thousands
// of repeats of the texture: a file whose texture coordinates reach 1e5 stalled the shadow pass
// for over 300 s. So a quad whose coordinates change by more than kMaxUVPerPixel repeats per
// pixel samples with explicit derivatives bounded to that, and coordinates wrapped into [0, 1)
// (every material sampler repeats): its footprint covers the texture many times over, and the
// last mips are read either way. Every other quad takes the plain texture() path, so sane scenes
// render the same pixels. The test is on coarse (per-quad) derivatives, so a quad never mixes the
// two paths, and the plain path is fed a constant on wide quads so its derivatives are zero there.
const float kMaxUVPerPixel = 8.0;

vec4 sampleMaterial(sampler2D tex, vec2 uv) {
    vec2 dx = dFdxCoarse(uv), dy = dFdyCoarse(uv);
    bool wide = !(max(max(abs(dx.x), abs(dx.y)), max(abs(dy.x), abs(dy.y))) <= kMaxUVPerPixel);
    vec4 c = texture(tex, wide ? vec2(0.0) : uv);
    if (wide) {
        vec2 bound = vec2(kMaxUVPerPixel);
        c = textureGrad(tex, fract(uv), clamp(dx, -bound, bound), clamp(dy, -bound, bound));
    }
    return c;
}
