#version 450 core
// Field overlays: the vertex colour, unlit, so a speed reads the same everywhere on screen.

in vec4 vColor;
out vec4 oColor;

void main() {
    oColor = vColor;
}
