#pragma once
/// \file BitmapFont.h
/// A tiny built-in bitmap font for legends and the viewer's heads-up line: 5 x 8 pixel cells
/// (baseline under row 6, row 7 for descenders), digits, lower-case letters (upper case is drawn
/// lower case) and . , - + / : % ( ) = and space. The glyphs are our own, drawn for this file.

#include <glm/vec2.hpp>
#include <string>
#include <vector>

namespace gale::render {

inline constexpr int GLYPH_WIDTH_PX = 5;
inline constexpr int GLYPH_HEIGHT_PX = 8;
inline constexpr int GLYPH_ADVANCE_PX = 6;  ///< one blank column between characters

/// True if font pixel (x, y) of `c` is lit; x in [0, 5) left to right, y in [0, 8) top down.
/// Characters the font lacks are blank (they still take their cell).
bool glyphPixel(char c, int x, int y);

/// True if the font has a glyph for `c` (space counts).
bool hasGlyph(char c);

/// Width in pixels of `text` drawn at integer `scale` (each font pixel a scale x scale block).
int textWidth_px(const std::string& text, int scale);

/// The lit font pixels of `text` as top-left corners in pixels, origin at the text's top-left,
/// x right, y down, at integer `scale` (>= 1).
std::vector<glm::ivec2> textPixels(const std::string& text, int scale);

}  // namespace gale::render
