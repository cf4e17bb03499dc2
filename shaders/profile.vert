#version 450 core
// The fill profile's layers (render/FillProfile.h): the benchmark's flat field drawn as N + 1
// layers like fill.vert (shell i extruded i S along the normal, alpha test at i / N), top first or
// bottom first, with a smooth per-vertex colour standing in for the shell's light.

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;

uniform mat4 uClipFromWorld;
uniform int uShells;          // N
uniform float uShellSpacing;  // S, metres
uniform int uBottomFirst;     // 1: instance k draws shell k; 0: shell N - k (the renderer's order)

out vec2 vUv;
out vec3 vLight;
flat out float vThreshold;

void main() {
    int i = (uBottomFirst != 0) ? gl_InstanceID : uShells - gl_InstanceID;
    gl_Position = uClipFromWorld * vec4(aPosition + aNormal * (float(i) * uShellSpacing), 1.0);
    vUv = aUv;
    vLight = vec3(0.8, 0.9, 0.7) + 0.004 * aPosition;
    float halfStep = 0.5 / 255.0;
    vThreshold = (i == 0) ? -1.0 : max(float(i) / float(max(uShells, 1)) - halfStep, halfStep);
}
