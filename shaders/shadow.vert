#version 450 core
// The key light's depth pass (render/ShadowMap.h): the terrain's positions, nothing else.

layout(location = 0) in vec3 aPosition;  // vertex on the terrain, world metres

uniform mat4 uClipFromWorld;  // the light's view and projection

void main() { gl_Position = uClipFromWorld * vec4(aPosition, 1.0); }
