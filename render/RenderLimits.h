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

/// The names these two had before constants were UPPER_CASE everywhere (docs/architecture.md),
/// kept only for app/scene/SceneParser and app/bench/BenchView, which are being rewritten; remove
/// them once those say MAX_LIGHTS and MAX_SHELLS.
constexpr int kMaxLights = MAX_LIGHTS;
constexpr int kMaxShells = MAX_SHELLS;

}  // namespace gale::render
