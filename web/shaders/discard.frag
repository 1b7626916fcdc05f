#version 300 es
// Fragment stage of the transform-feedback pass; never runs (RASTERIZER_DISCARD is on).
precision mediump float;
out vec4 fragColor;
void main() { fragColor = vec4(0.0); }
