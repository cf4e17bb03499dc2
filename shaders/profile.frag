#version 450 core
// The fill profile's fragment variants (render/FillProfile.h), one thing changed at a time from
// the trivial fill (fill.frag); the sampler's filter is set by the caller. Selected by FRAGMENT:
//   0  flat colour: no texture, no alpha test
//   1  flat colour, alpha test against a hash of the pixel (every layer's fragments shaded)
//   2  texture fetch and alpha test (fill.frag)
//   3  as 2, with the MIP level computed in the shader and passed to textureLod
//   4  as 2, times the per-vertex light (the shell fragment without density or level of detail)
//   5  as 2, plus 30 multiply-adds on the colour
//   6  as 2, plus a second fetch of the same texture
#ifndef FRAGMENT
#define FRAGMENT 2
#endif

uniform sampler2D uGrass;

in vec2 vUv;
in vec3 vLight;
flat in float vThreshold;

out vec4 oColor;

void main() {
#if FRAGMENT == 0
    oColor = vec4(vLight, 1.0);
#elif FRAGMENT == 1
    // A cheap hash of the pixel (integer, no texture) in [0, 1).
    uvec2 p = uvec2(gl_FragCoord.xy);
    uint h = (p.x * 1664525u) ^ (p.y * 1013904223u);
    h ^= h >> 13u;
    h *= 747796405u;
    if (float(h >> 8u) / 16777216.0 < vThreshold) discard;
    oColor = vec4(vLight, 1.0);
#else
#if FRAGMENT == 3
    // The level OpenGL would choose (the larger screen-space footprint), computed here.
    vec2 size = vec2(textureSize(uGrass, 0));
    vec2 dx = dFdx(vUv) * size;
    vec2 dy = dFdy(vUv) * size;
    float lod = 0.5 * log2(max(dot(dx, dx), dot(dy, dy)));
    vec4 texel = textureLod(uGrass, vUv, lod);
#else
    vec4 texel = texture(uGrass, vUv);
#endif
    if (texel.a < vThreshold) discard;
    vec3 color = texel.rgb;
#if FRAGMENT == 4
    color *= vLight;
#elif FRAGMENT == 5
    for (int k = 0; k < 10; ++k) color = color * 0.99 + vLight * 0.01;
#elif FRAGMENT == 6
    color += 0.01 * texture(uGrass, vUv * 1.37).rgb;
#endif
    oColor = vec4(color, 1.0);
#endif
}
