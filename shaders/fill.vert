#version 450 core
// Baseline for benchmarks: the same shells as shell.vert, in the same top-first order (shell
// i = N - gl_InstanceID, extruded i S along
// the normal) without bend or lighting, so its cost is geometry plus a textured alpha-tested fill.

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;

uniform mat4 uClipFromWorld;
uniform int uShells;          // N
uniform float uShellSpacing;  // S, metres

out vec2 vUv;
flat out float vThreshold;

void main() {
    int i = uShells - gl_InstanceID;
    gl_Position = uClipFromWorld * vec4(aPosition + aNormal * (float(i) * uShellSpacing), 1.0);
    vUv = aUv;
    float halfStep = 0.5 / 255.0;
    vThreshold = (i == 0) ? -1.0 : max(float(i) / float(max(uShells, 1)) - halfStep, halfStep);
}
