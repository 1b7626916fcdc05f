#version 300 es
// Fragment stage of the transfer textures' depth prepass (texel_prt.vert): only depth is
// wanted, colour writes are masked off, so the value written here is never seen.
precision mediump float;
out vec4 fragColor;
void main() { fragColor = vec4(0.0); }
