#version 450 core
// The key light's depth pass (render/ShadowMap.h): depth only, no colour attachment.

void main() {}
