// Transfer curves and tone mapping.
vec3 linearToSRGB(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// Narkowicz 2015 fit of the ACES reference rendering transform.
vec3 toneACES(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 toneMap(vec3 c, int op) {
    if (op == kToneReinhard) return c / (1.0 + c);
    if (op == kToneACES) return toneACES(c);
    return clamp(c, 0.0, 1.0);
}
