#pragma once
/// \file ViewInput.h
/// Input of `gale view` beyond the window's own events: scripted key presses (--keys) and mouse
/// actions (--input) for tests and demos, and the gestures that drop live wind into the flow
/// (a click, a shift-drag, the W, B and D keys; coupling/LiveWind.h).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "coupling/LiveWind.h"
#include "render/GlfwWindow.h"

namespace gale::app {

/// --keys: one character is one frame's key press ('>' the right arrow, ' ' space, '+' '-' '['
/// ']' as on the keyboard, letters; '.' and anything else no key).
render::InputEvent scriptedKey(char c);

/// --input: "FRAME:ACTION:X,Y[,X2,Y2];..." with window pixels (origin top-left) and ACTION one of
/// click (a left click), gust (a shift-drag from X,Y to X2,Y2), whirlwind, blast, downwash (the W,
/// B, D keys with the cursor at X,Y). Returns the events of each frame (0-based), in order, as
/// the window would deliver them. Throws InputError naming --input, the entry and the reason.
std::map<int, std::vector<render::InputEvent>> parseInputScript(const std::string& text);

/// A live source asked for in window pixels (coupling::pickTerrain places it).
struct LiveRequest {
    coupling::LiveSourceKind kind = coupling::LiveSourceKind::Whirlwind;
    double x_px = 0.0, y_px = 0.0;    ///< where (the click, the drag's start, the cursor)
    double x2_px = 0.0, y2_px = 0.0;  ///< gust front: the drag's end
};

/// Turns mouse and key events into live-wind requests: a left click (press and release less than
/// CLICK_SLOP_PX apart, no shift) drops a whirlwind; a shift + left drag launches a gust front
/// along the drag; W, B and D drop a whirlwind, a blast and a downwash at the cursor. A left drag
/// without shift stays the camera's orbit.
class LiveGestures {
  public:
    /// Moves of a press that still count as a click, pixels.
    static constexpr double CLICK_SLOP_PX = 4.0;

    /// Feeds one event. Returns a request when the event completes a gesture. `consumed` is set
    /// when the camera must not also act on the event (a drag that is a gust front).
    std::optional<LiveRequest> handle(const render::InputEvent& e, bool& consumed);

  private:
    bool mPressed = false, mShift = false;
    double mPressX_px = 0.0, mPressY_px = 0.0, mMoved_px = 0.0;
};

}  // namespace gale::app
