#version 450 core
// Shell grass fragment shader (Bakay 2003, 3.1): the alpha test against this shell's height, then
// the texture colour times the per-vertex light, self-shadowed for the height at which the blade is
// seen. Opaque: no blending, depth test on.
//
// Two additions (docs/render.md): a density map thins the blades (a blade stays only where its
// height is above the cut that leaves the map's fraction of the texture's blade area), and the
// texture is laid aperiodically (each cell of a jittered grid over the texture plane shows the
// texture rotated by a multiple of 90 degrees, mirrored and shifted at random), so no repeat shows.
//
// Specialised by defines, one program per combination (ShellRenderer): a branch on a uniform is
// not free on llvmpipe, which runs the code of both sides under a lane mask. Measured: the unused
// aperiodic branch alone cost the shell pass 0.34 -> 0.80 of the trivial fill (docs/render.md).
//   APERIODIC  1: the jittered-cell layout; 0: the plain repeat
//   FADE       1: the level of detail's fade (vFade) thins the blades, and the blades of dropped
//              shells are shaded where they were seen; 0: every shell is drawn
//   DENSITY    1: the density map (uDensity) thins the blades
//   BLADES     1: the near level's blade geometry (shell.vert): the blade's colour, lit; no
//              texture and no alpha test (FADE and DENSITY are 0 with it)
#ifndef APERIODIC
#define APERIODIC 0
#endif
#ifndef FADE
#define FADE 0
#endif
#ifndef DENSITY
#define DENSITY 0
#endif
#ifndef BLADES
#define BLADES 0
#endif
#if BLADES  // the blades are placed and thinned on the CPU: no fade, no density map
#undef FADE
#define FADE 0
#undef DENSITY
#define DENSITY 0
#endif

uniform sampler2D uGrass;       // RGB colour, alpha = blade height fraction, blade-keeping MIP chain
uniform sampler2D uDensity;     // density in [0, 1] over the plan (R channel)
uniform sampler2D uDensityCut;  // 256 x 1: texel k is the alpha cut for density k / 255
uniform vec3 uBladeColor;       // mean colour of the texture's blade texels (level 0)

in vec2 vUv;
in vec2 vDensityUv;
in float vFade;
#if FADE && !DENSITY
in float vFadeCut;
#endif
in float vStandIn;
#if FADE
in vec3 vLit;
flat in float vShell;
in float vSpan;
in float vCover;
uniform int uShells;            // N
uniform vec3 uAmbient;
uniform float uShadowMin;       // Banks S_min
#else
in vec3 vLight;
#endif
flat in float vThreshold;

out vec4 oColor;

// A 32-bit integer hash (Jarzynski and Olano 2020, "Hash Functions for GPU Rendering": pcg2d).
uvec2 pcg2d(uvec2 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    return v;
}

#if APERIODIC
// The texture lookup of the aperiodic layout. Cells are the unit squares of the texture plane;
// each has a feature point jittered within +-0.25 of its centre, and a fragment belongs to the
// cell of the nearest feature point among the four cells around it (a Voronoi partition of a
// jittered grid: irregular borders, no straight seam). The cell's random transform (one of the 8
// symmetries of the square, then a shift) is applied to uv and, for the MIP level, to its screen
// derivatives: the transform is piecewise rigid, so the level is the plain repeat's.
vec4 aperiodicTexel(vec2 uv) {
    vec2 base = floor(uv - 0.5);
    vec2 best = base;
    float bestD = 1e9;
    for (int k = 0; k < 4; ++k) {
        vec2 cell = base + vec2(k & 1, k >> 1);
        uvec2 h = pcg2d(uvec2(ivec2(cell) + 32768));
        vec2 point = cell + 0.5 + (vec2(h & 0xffffu) / 65535.0 - 0.5) * 0.5;
        vec2 d = uv - point;
        float dd = dot(d, d);
        if (dd < bestD) {
            bestD = dd;
            best = cell;
        }
    }
    uvec2 h = pcg2d(uvec2(ivec2(best) + 32768) ^ uvec2(0x9e3779b9u, 0x85ebca6bu));
    uint sym = h.x & 7u;
    vec2 shift = vec2(h >> 16u) / 65536.0;
    // Symmetry: mirror x if bit 2, then rotate by 90 degrees times (bits 0-1).
    mat2 m = ((sym & 4u) != 0u) ? mat2(-1.0, 0.0, 0.0, 1.0) : mat2(1.0);
    uint r = sym & 3u;
    mat2 rot = (r == 0u) ? mat2(1.0) : (r == 1u) ? mat2(0.0, 1.0, -1.0, 0.0)
             : (r == 2u) ? mat2(-1.0, 0.0, 0.0, -1.0) : mat2(0.0, -1.0, 1.0, 0.0);
    m = rot * m;
    return textureGrad(uGrass, m * uv + shift, m * dFdx(uv), m * dFdy(uv));
}
#endif

#if BLADES
in vec3 vColor;
void main() { oColor = vec4(vColor * vLight, 1.0); }
#else
void main() {
#if APERIODIC
    vec4 texel = aperiodicTexel(vUv);
#else
    vec4 texel = texture(uGrass, vUv);
#endif
    float threshold = vThreshold;
#if FADE && !DENSITY
    // The level of detail's fade alone: its cut comes from the vertex stage (shell.vert).
    threshold = max(threshold, vFadeCut);
#elif FADE || DENSITY
    // The map's density times the level of detail's fade (render/TerrainChunks.h).
    float density = 1.0;
#if FADE
    density *= vFade;
#endif
#if DENSITY
    density *= clamp(texture(uDensity, vDensityUv).r, 0.0, 1.0);
#endif
    if (density < 1.0 && threshold > 0.0) {
        // The cut that keeps this share of blade area: blades shorter than it vanish whole, the
        // others keep their full height.
        float cut = texture(uDensityCut, vec2((density * 255.0 + 0.5) / 256.0, 0.5)).r;
        threshold = max(threshold, cut);
    }
#endif
    if (texel.a < threshold) discard;
#if FADE
    // The far ground standing in for the dropped grass (shell.vert) shows the blades' colour.
    texel.rgb = mix(texel.rgb, uBladeColor, vStandIn);
    // Banks 1994 self-shadowing (thesis 3.3.3): S = (D_cur / D_max)(1 - S_min) + S_min, with
    // D_cur / D_max = k / N for the shell k the blade is seen on; ambient added after attenuation
    // and shadowing (thesis 3.3.4). With every shell drawn k = i. Where the level of detail has
    // dropped the vSpan shells above this one, a ray that would have stopped on one of them at
    // this texel now reaches this shell: seen from above, on the highest shell that keeps the
    // texel, floor(N alpha) (shell.vert's alpha test), so the blade keeps the brightness it had
    // and no darker band shows where shells are dropped (tests/render/SeamTest.cpp).
    float n = float(max(uShells, 1));
    float seen = clamp(floor((texel.a + 0.5 / 255.0) * n), vShell, vShell + vSpan);
    // On the ground, the share vCover of rays the dropped shells would have stopped shows a blade
    // of the mean colour halfway up them (shell.vert).
    seen = mix(seen, vShell + 0.5 * (vSpan + 1.0), vCover);
    texel.rgb = mix(texel.rgb, uBladeColor, vCover);
    float S = seen / n * (1.0 - uShadowMin) + uShadowMin;
    S = mix(S, 1.0, vStandIn);
    oColor = vec4(texel.rgb * (vLit * S + uAmbient), 1.0);
#else
    oColor = vec4(texel.rgb * vLight, 1.0);
#endif
}
#endif
