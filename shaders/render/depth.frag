// Depth pre-pass of the G-buffer's Opaque draws (gbuffer.vert positions them): no colour, no
// discard, so the depth test runs before this empty body and the G-buffer pass that follows
// shades each pixel's nearest opaque surface once instead of every surface drawn over it.
void main() {}
