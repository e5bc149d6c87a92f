// Transfer curves and tone mapping.
vec3 linearToSRGB(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// The tone curves live in common/shared.h, shared with the C++ that tone maps references.
vec3 toneMap(vec3 c, int op) {
    return vec3(giToneChannel(c.r, op), giToneChannel(c.g, op), giToneChannel(c.b, op));
}
