#version 450 core
// Shell grass vertex shader (Bakay, Lalonde, Heidrich 2002; Bakay 2003, chapter 3).
// One instance per shell, drawn top first: shell i = uTopShell - gl_InstanceID (0 = ground, N =
// top; uTopShell = N unless the viewer hides the grass); see
// ShellRenderer::draw for why. Everything here is world space,
// metres; lighting is evaluated per vertex, as in the thesis, except that with the level of detail's
// FADE the fragment stage applies the self-shadowing of the shell the blade is seen on.

// Specialised by defines (ShellRenderer compiles one program per combination, see shell.frag):
//   BLEND_GROUPS  1: blend the four nearest groups at aGroupCoord (bilinear), so no stripes show
//                 where groups change; 0: this vertex's group alone.
//   FADE          1: the level of detail's work in chunks that thin or drop shells: pass the
//                 fade to the fragment stage (without DENSITY as the alpha cut it implies, one
//                 lookup per vertex instead of per fragment), and what the fragment stage needs
//                 to shade the blades of dropped shells where they were seen; 0: every shell
//                 drawn, self-shadowing per vertex.
//   DENSITY       1: a density map thins the blades too (the fragment stage looks the cut up).
//   BLADES        1: not a shell but the near level's blade geometry (render/NearBlades.h): one
//                 instance per blade, a strip of 2 BLADES_SEGMENTS + 1 vertices up the curve the
//                 shells' bend tables give its root, lit as the shells are at each height.
//                 FADE and DENSITY are 0 with it (the CPU placed and thinned the blades).
#ifndef BLEND_GROUPS
#define BLEND_GROUPS 0
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
#ifndef BLADES_SEGMENTS
#define BLADES_SEGMENTS 5
#endif

// Must equal gale::render::MAX_LIGHTS (render/RenderLimits.h); ShellRenderer checks the array size.
#define MAX_LIGHTS 16

#if BLADES
// One blade per instance (render/NearBlades.h, BladeInstance).
layout(location = 0) in vec3 aPosition;  // the blade's root on the terrain
layout(location = 1) in vec3 aNormal;    // unit terrain normal at the root
// Height as a fraction of the grass height, width (m), facing (radians about the normal), tilt
// factor (a stiffer blade bends less).
layout(location = 2) in vec4 aBlade;
layout(location = 3) in vec3 aWindDir;   // unit tangent-plane wind direction, or zero
layout(location = 4) in uint aGroup;     // the root's nearest vertex's group
layout(location = 5) in vec2 aGroupCoord; // position in the group grid (when BLEND_GROUPS)
layout(location = 6) in float aFlutter;   // turbulent flutter amplitude of the tip tilt, radians
layout(location = 7) in vec4 aColor;      // linear RGB, then the key light's share at the root
out vec3 vColor;
out vec3 vBladeWorld;  // the vertex, world metres (ShellRenderer::captureNearBlades records it)
#else
layout(location = 0) in vec3 aPosition;  // vertex on the terrain
layout(location = 1) in vec3 aNormal;    // unit terrain normal
layout(location = 2) in vec2 aUv;        // grass texture coordinates
layout(location = 3) in vec3 aWindDir;   // unit tangent-plane wind direction, or zero
layout(location = 4) in uint aGroup;     // animation-step group
layout(location = 5) in vec2 aGroupCoord; // position in the group grid (when BLEND_GROUPS)
layout(location = 6) in float aFlutter;   // turbulent flutter amplitude of the tip tilt, radians
// Share of the key light (light 0) that passes the terrain to this vertex, [0, 1], from its
// shadow map (render/ShadowMap.h), at each mesh level (.x-.w levels 0-3, then 4-5): at a coarse
// level, the mean over the ground its cells stand for. 1 without a map. The blades over a vertex
// share its value.
layout(location = 7) in vec4 aKeyLight0;
layout(location = 8) in vec2 aKeyLight4;
#endif
uniform int uMeshLevel;  // the mesh level this draw's chunk takes (render/TerrainChunks.h)

uniform mat4 uClipFromWorld;
uniform vec3 uEyePos;          // camera position
uniform int uShells;           // N
uniform int uTopShell;         // shell of instance 0: N, or 0 when the grass is hidden (viewer)
uniform int uShellStride;      // instance k draws shell uTopShell - k uShellStride (LOD)
// Level of detail (render/TerrainChunks.h): shell i thins out between 0.7 D(i) and D(i), D(i) =
// uLodD1 2^(trailing zero bits of i), metres from the eye; 0 = no level of detail.
uniform float uLodD1;
// The shell the level of detail drops last: the largest power of two <= N (render/TerrainChunks.h).
uniform int uLastShell;
uniform float uTime_s;         // the wind's time (GrassWind::time_s), seconds
// The near blades' distances R_in and R (render/NearBlades.h), metres; R = 0: none. Within R the
// blade geometry takes over from shells 1..N: they thin out towards R_in as the blades thin out
// towards R, and are clipped away inside R_in (gl_ClipDistance[0], so those fragments are never
// shaded); the ground stays.
uniform float uNearIn;
uniform float uNearR;
// Bends over tip tilts (render/BendTables.h): texel (i, l) holds (n_i, w_i) in metres for shell i
// of a blade whose tip tilts by -uMaxTilt + 2 uMaxTilt l / (L - 1) (Bakay 2003, 3.2), and in .ba
// segment i, (n_i - n_{i-1}, w_i - w_{i-1}): interpolated between rows like the offsets, it is
// exactly the difference of the two interpolated shell positions, so one fetch pair gives both.
uniform sampler2D uBend;
uniform float uMaxTilt;        // radians
// Tip tilt per group this frame (radians), groups row by row uGroupColumns wide.
uniform sampler2D uGroupTilt;
uniform int uGroupColumns;

uniform int uLightCount;
uniform vec3 uLightPos[MAX_LIGHTS];
uniform vec3 uLightColor[MAX_LIGHTS];
uniform vec3 uLightAtten[MAX_LIGHTS];  // (k_c, k_l, k_q)
uniform float uSpecularPower;
uniform float uSpecularStrength;

// The density map's plan rectangle (render/DensityMap.h), metres.
uniform vec2 uDensityMin;
uniform vec2 uDensitySize;

out vec2 vUv;
out vec2 vDensityUv;       // where the blade's root is on the density map (row 0 = north)
out float vFade;           // share of this shell's blades the level of detail keeps, [0, 1]
#if FADE && !DENSITY
// The alpha cut for vFade (render/DensityMap.h), looked up per vertex: with no density map the fade
// is the only density, a smooth function of the distance, so the cut is interpolated across a
// triangle instead of the fade (measured: 3-5 % of a frame on llvmpipe, docs/render.md).
uniform sampler2D uDensityCut;
out float vFadeCut;
#endif
out float vStandIn;        // ground only: how far it stands in for the dropped grass, [0, 1]
#if FADE
out vec3 vLit;             // key light reaching the vertex before self-shadowing (fragment: S)
flat out float vShell;     // this shell's index i
// How many shells above this one the level of detail has dropped (fractionally while they thin
// out): their blades are now seen on this shell, which is shaded at the height they had.
out float vSpan;
// Ground only: the share of rays reaching it that the dropped shells above it would have stopped
// on a blade (seen at a slant, a ray crosses each shell at a texel of its own); shell.frag shows
// that share as the grass it hides.
out float vCover;
// Pass table (render/DensityMap.h, shellPassFractions): texel m, the share of rays that cross
// shells 1..m at texels of their own without stopping on a blade.
uniform sampler2D uShellPass;
uniform float uShellFocal;  // S f: the shell spacing (metres) times the focal length (pixels)
#else
out vec3 vLight;           // light reaching the vertex, multiplies the texture colour
uniform vec3 uAmbient;
uniform float uShadowMin;  // Banks S_min
#endif
flat out float vThreshold; // alpha test: keep texels with alpha >= vThreshold

float groupTilt() {
#if BLEND_GROUPS
    vec2 size = vec2(textureSize(uGroupTilt, 0));
    return texture(uGroupTilt, (aGroupCoord + 0.5) / size).r;
#else
    int g = int(aGroup);
    return texelFetch(uGroupTilt, ivec2(g % uGroupColumns, g / uGroupColumns), 0).r;
#endif
}

// The bend of shell i at tilt row `row` (fractional), linear between the two nearest rows:
// (n_i, w_i, segment n, segment w), metres.
vec4 shellBend(int i, float row) {
    int last = textureSize(uBend, 0).y - 1;
    int r0 = min(int(row), last);
    vec4 a = texelFetch(uBend, ivec2(i, r0), 0);
    vec4 b = texelFetch(uBend, ivec2(i, min(r0 + 1, last)), 0);
    return mix(a, b, row - float(r0));
}

// A smoothed triangle wave in [-1, 1] of period 1 (the cheap stand-in for a sine of the detail
// bending in Sousa 2008, GPU Gems 3 ch. 16, section 16.4: |2 frac(x + 1/2) - 1| through the
// smoothstep cubic).
float smoothTriangle(float x) {
    float t = abs(2.0 * fract(x + 0.5) - 1.0);
    return 2.0 * t * t * (3.0 - 2.0 * t) - 1.0;
}

// The turbulent flutter of the tip tilt at this vertex, radians: aFlutter times two incommensurate
// waves (0.9 and 2.3 Hz, the range of grass's first bending modes; unit peak), their phases set
// per vertex by a hash of its plan position so neighbouring patches move out of step: agitation
// where the air is turbulent, stillness where aFlutter is 0 (calm or sheltered air).
float flutterTilt() {
    if (aFlutter <= 0.0) return 0.0;
#if BLADES
    // Each blade its own phase (its root's 1 cm cell).
    uvec2 h = uvec2(ivec2(floor(aPosition.xy * 100.0)) + (1 << 30));
#else
    uvec2 h = uvec2(ivec2(floor(aPosition.xy * 4.0)) + 32768);
#endif
    h = h * 1664525u + 1013904223u;
    h.x += h.y * 1664525u;
    h.y += h.x * 1664525u;
    h ^= h >> 16u;
    vec2 phase = vec2(h & 0xffffu) / 65535.0;
    float wave = 0.6 * smoothTriangle(0.9 * uTime_s + phase.x) +
                 0.4 * smoothTriangle(2.3 * uTime_s + phase.y);
    return aFlutter * wave;
}

// Kajiya and Kay 1989 strand lighting at `pos` for the strand tangent T (thesis 3.3.1-3.3.4):
// the lights' sum, attenuated, the key light scaled by `key` (its share past the terrain).
vec3 strandLight(vec3 pos, vec3 T, float key) {
    vec3 V = normalize(uEyePos - pos);
    vec3 lit = vec3(0.0);
    for (int l = 0; l < uLightCount; ++l) {
        vec3 toLight = uLightPos[l] - pos;
        float d = length(toLight);
        vec3 L = toLight / max(d, 1e-6);
        vec3 H = normalize(L + V);
        // The best normal on the strand's normal disk gives cos = sqrt(1 - (T.L)^2) for diffuse
        // and sqrt(1 - (T.H)^2) for the highlight.
        float tl = dot(T, L);
        float th = dot(T, H);
        float diffuse = sqrt(max(1.0 - tl * tl, 0.0));
        float specular = uSpecularStrength * pow(sqrt(max(1.0 - th * th, 0.0)), uSpecularPower);
        // Thesis 3.3.4: 1 / (k_c + k_l d + k_q d^2).
        vec3 k = uLightAtten[l];
        float attenuation = 1.0 / max(k.x + k.y * d + k.z * d * d, 1e-6);
        lit += uLightColor[l] * (attenuation * (diffuse + specular) * (l == 0 ? key : 1.0));
    }
    return lit;
}

#if BLADES
// A blade of height fraction f = aBlade.x is the lower part, up to f of its length, of the full
// blade the bend tables describe at its root (the shells show a shorter texel blade the same
// way: on the shells up to its height, at the full blade's positions). Vertex k of the strip:
// level k / 2 of BLADES_SEGMENTS, on the left (even) or right (odd) edge; the last is the tip.
void main() {
    int level = min(gl_VertexID / 2, BLADES_SEGMENTS);
    float side = (gl_VertexID == 2 * BLADES_SEGMENTS) ? 0.0 : ((gl_VertexID & 1) == 0 ? -0.5 : 0.5);
    float last = float(textureSize(uBend, 0).y - 1);
    float tilt = (groupTilt() + flutterTilt()) * aBlade.w;
    float row = clamp((tilt / uMaxTilt * 0.5 + 0.5) * last, 0.0, last);
    float along = aBlade.x * float(level) / float(BLADES_SEGMENTS);  // of the full length
    float column = along * float(uShells);
    int c0 = min(int(column), uShells - 1);
    vec4 b0 = shellBend(c0, row);
    vec4 b1 = shellBend(c0 + 1, row);
    vec2 nw = mix(b0.xy, b1.xy, column - float(c0));
    // Across the blade: a tangent direction turned by the blade's own facing about the normal,
    // whatever the wind (a blade does not turn to face it; only its bend follows the wind).
    vec3 any = abs(aNormal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 t0 = normalize(cross(aNormal, any));
    vec3 across = cos(aBlade.z) * t0 + sin(aBlade.z) * cross(aNormal, t0);
    float taper = 1.0 - float(level) / float(BLADES_SEGMENTS);
    vec3 spine = aPosition + nw.x * aNormal + nw.y * aWindDir;
    vec3 pos = spine + (side * aBlade.y * sqrt(taper)) * across;
    gl_Position = uClipFromWorld * vec4(pos, 1.0);
    vBladeWorld = pos;
    vUv = vec2(0.0);
    vDensityUv = vec2(0.0);
    vFade = 1.0;
    vStandIn = 0.0;
    vThreshold = -1.0;
    vColor = aColor.rgb;
    // The strand tangent of the segment this vertex starts (the tip: the last one's).
    vec3 T = normalize(b1.z * aNormal + b1.w * aWindDir);
    vec3 lit = strandLight(pos, T, aColor.a);
    // Banks 1994 self-shadowing at the height the vertex is at, as on the shell of that height.
    float S = along * (1.0 - uShadowMin) + uShadowMin;
    vLight = lit * S + uAmbient;
}
#else
out float gl_ClipDistance[1];
void main() {
    int i = uTopShell - gl_InstanceID * uShellStride;
    float last = float(textureSize(uBend, 0).y - 1);
    float tilt = groupTilt() + flutterTilt();
    float row = clamp((tilt / uMaxTilt * 0.5 + 0.5) * last, 0.0, last);
    vec4 bend = shellBend(i, row);
    vec3 pos = aPosition + bend.x * aNormal + bend.y * aWindDir;
    gl_Position = uClipFromWorld * vec4(pos, 1.0);
    vUv = aUv;
    vec2 plan = (aPosition.xy - uDensityMin) / uDensitySize;
    vDensityUv = vec2(plan.x, 1.0 - plan.y);
    vFade = 1.0;
    vStandIn = 0.0;
    gl_ClipDistance[0] = 1.0;
#if FADE
    // The level of detail drops a shell whole at its distance (render/TerrainChunks.h,
    // shellRange) and does not thin it before: thinning by the density cut removes the short
    // blades first, so rays reach the darker lower shells early and the thinning band showed up
    // to 7 levels darker per 32 x 32 tile than every shell drawn (tests/render/SeamTest.cpp); the
    // drop is shaded by vSpan below. Only the hand-over to the near blades thins the shells.
    if (uNearR > 0.0 && i > 0) {
        float eye = distance(aPosition, uEyePos);
        vFade *= smoothstep(uNearIn, uNearR, eye);
        gl_ClipDistance[0] = eye - uNearIn;
    }
#if !DENSITY
    // Shell 0 keeps every texel; a full fade's cut is 0 (every blade kept).
    vFadeCut = (i > 0)
                   ? textureLod(uDensityCut, vec2((vFade * 255.0 + 0.5) / 256.0, 0.5), 0.0).r
                   : -1.0;
#endif
    // Where the last shell thins out the ground alone remains; it takes over the look of the
    // grass it replaces (shaded as the top layer, in the mean blade colour), at the same pace, so
    // the far field keeps the grass's brightness instead of the shaded soil's.
    if (uLodD1 > 0.0 && i == 0 && uLastShell > 0) {
        float drop = uLodD1 * float(uLastShell);
        vStandIn = smoothstep(0.7 * drop, drop, distance(aPosition, uEyePos));
    }
    // The dropped shells this one stands for (render/TerrainChunks.h): the shells between i and
    // the next drawn shell above it, i + 1 .. i + 2^v(i) - 1 (v the trailing zero bits; for the
    // ground every shell up to the last dropped), are dropped level by level, 2^l of them at
    // level l, each thinning out over 0.7 D1 2^l .. D1 2^l like its fade above.
    // The levels' ramps do not overlap (0.7 D1 2^(l+1) > D1 2^l): at distance d the levels
    // l < L = floor(log2(d / D1)) + 1 are dropped whole, 2^L - 1 shells, and level L is
    // thinning; the sum stops at the levels below v(i).
    vShell = float(i);
    vSpan = 0.0;
    if (uLodD1 > 0.0) {
        float eye = distance(aPosition, uEyePos);
        float levels = (i == 0) ? float(findLSB(max(uLastShell, 1)) + 1) : float(findLSB(i));
        float whole = (eye >= uLodD1) ? floor(log2(eye / uLodD1)) + 1.0 : 0.0;
        float next = exp2(whole);
        float partial = next * smoothstep(0.7 * uLodD1 * next, uLodD1 * next, eye);
        vSpan = (whole >= levels) ? exp2(levels) - 1.0
                                  : next - 1.0 + partial;
        vSpan = min(vSpan, float(uShells - i));
    }
    // Straight down, a ray crosses every shell at the same texel, which is why shell.frag's seen
    // shell is exact there, and the dropped shells hide nothing the ground's texel does not show.
    // At a slant it crosses them at independent texels, and would have stopped on one of them
    // with probability 1 - pass(span), once its crossings are a pixel's footprint apart: they
    // are S sin(theta) / cos(theta) apart on the ground and the footprint is d / (f cos(theta))
    // long, so the ratio is S f sin(theta) / d (theta from the normal, d the distance).
    vCover = 0.0;
    if (i == 0 && vSpan > 0.0) {
        int m0 = int(vSpan);
        float pass0 = texelFetch(uShellPass, ivec2(m0, 0), 0).r;
        float pass1 = texelFetch(uShellPass, ivec2(min(m0 + 1, uShells), 0), 0).r;
        float pass = mix(pass0, pass1, vSpan - float(m0));
        vec3 toEye = uEyePos - aPosition;
        float d = max(length(toEye), 1e-6);
        float mu = min(abs(dot(toEye, aNormal)) / d, 1.0);
        float apart = sqrt(1.0 - mu * mu) * uShellFocal / d;
        vCover = (1.0 - pass) * min(apart, 1.0);
    }
#endif

    // Thesis 3.1: shell i keeps texels with alpha >= i/N; the ground keeps every texel. Half an
    // 8-bit step of slack so a blade of alpha 255 i/N passes its shell despite rounding; never
    // below half a step, so bare ground (alpha 0) never shows above shell 0.
    float halfStep = 0.5 / 255.0;
    vThreshold = (i == 0) ? -1.0 : max(float(i) / float(max(uShells, 1)) - halfStep, halfStep);

    // Strand tangent (thesis 3.3.1): from this vertex on shell i-1 to shell i; the ground uses the
    // terrain normal.
    vec3 T = (i == 0) ? aNormal : normalize(bend.z * aNormal + bend.w * aWindDir);
    float key = (uMeshLevel < 4) ? aKeyLight0[uMeshLevel] : aKeyLight4[uMeshLevel - 4];
    vec3 lit = strandLight(pos, T, key);
#if FADE
    // The self-shadowing and the ambient term are applied per fragment (shell.frag), where the
    // texel says which dropped shell a blade would have been seen on.
    vLit = lit;
#else
    // Banks 1994 self-shadowing (thesis 3.3.3): S = (D_cur / D_max)(1 - S_min) + S_min with
    // D_cur / D_max = i / N; ambient added after attenuation and shadowing (thesis 3.3.4).
    float S = float(i) / float(max(uShells, 1)) * (1.0 - uShadowMin) + uShadowMin;
    vLight = lit * S + uAmbient;
#endif
}
#endif
