#version 450 core
// Shell grass fragment shader (Bakay 2003, 3.1): the alpha test against this shell's height, then
// the texture colour times the per-vertex light. Opaque: no blending, depth test on.

uniform sampler2D uGrass;  // RGB colour, alpha = blade height fraction, blade-keeping MIP chain

in vec2 vUv;
in vec3 vLight;
flat in float vThreshold;

out vec4 oColor;

void main() {
    vec4 texel = texture(uGrass, vUv);
    if (texel.a < vThreshold) discard;
    oColor = vec4(texel.rgb * vLight, 1.0);
}
