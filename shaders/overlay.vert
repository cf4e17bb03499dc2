#version 450 core
// Field overlays (render/FieldOverlay): flat-coloured triangles, either in world space (arrows,
// slice, streamline ribbons, vortex-core markers; uClipFromWorld = the camera's) or already in
// clip space (legend and text; uClipFromWorld = identity). Colours arrive as sRGB with alpha.

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColor;

uniform mat4 uClipFromWorld;

out vec4 vColor;

void main() {
    gl_Position = uClipFromWorld * vec4(aPosition, 1.0);
    vColor = aColor;
}
