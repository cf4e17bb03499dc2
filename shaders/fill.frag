#version 450 core
// Baseline for benchmarks: texture fetch and alpha test only.

uniform sampler2D uGrass;

in vec2 vUv;
flat in float vThreshold;

out vec4 oColor;

void main() {
    vec4 texel = texture(uGrass, vUv);
    if (texel.a < vThreshold) discard;
    oColor = vec4(texel.rgb, 1.0);
}
