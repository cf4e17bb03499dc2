#pragma once
/// \file RenderLimits.h
/// Hard limits of the shell renderer, in one place so the scene parser can refuse a scene before
/// any GL work starts.

namespace gale::render {

/// Most point lights the shell vertex shader evaluates (uniform arrays in shaders/shell.vert are
/// sized by this; the thesis used 3). ShellRenderer::setLighting throws std::invalid_argument
/// above it, and a scene naming more lights must be refused with that message.
constexpr int MAX_LIGHTS = 16;

/// Most shells above the ground (GrassParams::shells); the bend table has MAX_SHELLS + 1 columns.
constexpr int MAX_SHELLS = 256;

/// Most near blades a frame draws (GrassParams::nearBlades): 1 M blades are 88 MB of instances.
constexpr int MAX_NEAR_BLADES = 1000000;

}  // namespace gale::render
