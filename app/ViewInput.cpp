/// \file ViewInput.cpp
/// Scripted input and live-wind gestures of `gale view` (see ViewInput.h).

#include "app/ViewInput.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <system_error>

#include "app/io/Errors.h"

namespace gale::app {
namespace {

render::InputEvent mouseButton(bool pressed, double x_px, double y_px, int mods) {
    render::InputEvent e;
    e.kind = render::InputEvent::Kind::MouseButton;
    e.button = 0;
    e.pressed = pressed;
    e.mods = mods;
    e.x_px = x_px;
    e.y_px = y_px;
    return e;
}

render::InputEvent keyAt(render::Key key, double x_px, double y_px) {
    render::InputEvent e;
    e.kind = render::InputEvent::Kind::Key;
    e.key = key;
    e.x_px = x_px;
    e.y_px = y_px;
    return e;
}

}  // namespace

render::InputEvent scriptedKey(char c) {
    render::InputEvent e;
    e.kind = render::InputEvent::Kind::Key;
    switch (c) {
        case '>':
            e.key = render::Key::Right;
            break;
        case ' ':
            e.key = render::Key::Space;
            break;
        case '+':
            e.key = render::Key::Equal;
            break;
        case '-':
            e.key = render::Key::Minus;
            break;
        case '[':
            e.key = render::Key::LeftBracket;
            break;
        case ']':
            e.key = render::Key::RightBracket;
            break;
        default:
            e.key = render::letterKey(c);  // '.' and anything else: no key this frame
            break;
    }
    return e;
}

namespace {

/// `text` without leading and trailing spaces and tabs.
std::string trimmed(const std::string& text) {
    const size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

}  // namespace

std::map<int, std::vector<render::InputEvent>> parseInputScript(const std::string& text) {
    std::map<int, std::vector<render::InputEvent>> script;
    std::stringstream entries(text);
    std::string entry;
    while (std::getline(entries, entry, ';')) {
        if (entry.find_first_not_of(" \t") == std::string::npos) continue;
        auto bad = [&](const std::string& why) {
            return InputError("--input: entry '" + entry + "': " + why +
                              " (expected FRAME:ACTION:X,Y[,X2,Y2], ACTION click, gust, "
                              "whirlwind, blast or downwash)");
        };
        // Strict: FRAME:ACTION:COORDS, each part whole (no trailing characters, no hex).
        const size_t colon1 = entry.find(':');
        const size_t colon2 = colon1 == std::string::npos ? colon1 : entry.find(':', colon1 + 1);
        if (colon2 == std::string::npos) throw bad("cannot read FRAME:ACTION:");
        const std::string frameText = trimmed(entry.substr(0, colon1));
        const std::string action = trimmed(entry.substr(colon1 + 1, colon2 - colon1 - 1));
        if (frameText.empty() || frameText.find_first_not_of("0123456789") != std::string::npos)
            throw bad("FRAME '" + frameText + "' must be a whole number >= 0 (decimal digits)");
        long long frameValue = 0;
        const auto [frameEnd, frameErr] =
            std::from_chars(frameText.data(), frameText.data() + frameText.size(), frameValue);
        if (frameErr != std::errc() || frameEnd != frameText.data() + frameText.size() ||
            frameValue > std::numeric_limits<int>::max())
            throw bad("FRAME " + frameText + " is beyond the last frame the viewer counts to (" +
                      std::to_string(std::numeric_limits<int>::max()) + ")");
        const int frame = static_cast<int>(frameValue);
        if (action.empty() ||
            action.find_first_not_of("abcdefghijklmnopqrstuvwxyz") != std::string::npos)
            throw bad("cannot read FRAME:ACTION:");
        double c[4] = {0, 0, 0, 0};
        int read = 0;
        {
            std::stringstream coords(entry.substr(colon2 + 1));
            std::string raw;
            while (std::getline(coords, raw, ',')) {
                if (read == 4) throw bad("more than 4 coordinates");
                const std::string number = trimmed(raw);
                // Decimal only: strtod would also take hex ("0x10"), "inf" and "nan".
                char* end = nullptr;
                const bool decimal = !number.empty() && number.find_first_not_of(
                                                            "0123456789+-.eE") == std::string::npos;
                if (decimal) c[read] = std::strtod(number.c_str(), &end);
                if (!decimal || end != number.c_str() + number.size() || !std::isfinite(c[read]))
                    throw bad("'" + raw + "' is not a pixel coordinate");
                ++read;
            }
            if (!entry.empty() && entry.back() == ',') throw bad("a coordinate is missing");
        }
        const std::string& a = action;
        std::vector<render::InputEvent>& events = script[frame];
        if (a == "gust") {
            if (read != 4) throw bad("gust needs X,Y,X2,Y2");
            events.push_back(mouseButton(true, c[0], c[1], render::MOD_SHIFT));
            render::InputEvent drag;
            drag.kind = render::InputEvent::Kind::MouseDrag;
            drag.mods = render::MOD_SHIFT;
            drag.dx = c[2] - c[0];
            drag.dy = c[3] - c[1];
            drag.x_px = c[2];
            drag.y_px = c[3];
            events.push_back(drag);
            events.push_back(mouseButton(false, c[2], c[3], render::MOD_SHIFT));
            continue;
        }
        if (read != 2) throw bad(a + " needs X,Y");
        if (a == "click") {
            events.push_back(mouseButton(true, c[0], c[1], render::MOD_NONE));
            events.push_back(mouseButton(false, c[0], c[1], render::MOD_NONE));
        } else if (a == "whirlwind") {
            events.push_back(keyAt(render::Key::W, c[0], c[1]));
        } else if (a == "blast") {
            events.push_back(keyAt(render::Key::B, c[0], c[1]));
        } else if (a == "downwash") {
            events.push_back(keyAt(render::Key::D, c[0], c[1]));
        } else {
            throw bad("unknown action '" + a + "'");
        }
    }
    return script;
}

std::optional<LiveRequest> LiveGestures::handle(const render::InputEvent& e, bool& consumed) {
    using K = render::InputEvent::Kind;
    consumed = false;
    LiveRequest r;
    r.x_px = r.x2_px = e.x_px;
    r.y_px = r.y2_px = e.y_px;
    if (e.kind == K::Key) {
        if (e.key == render::Key::W)
            r.kind = coupling::LiveSourceKind::Whirlwind;
        else if (e.key == render::Key::B)
            r.kind = coupling::LiveSourceKind::Blast;
        else if (e.key == render::Key::D)
            r.kind = coupling::LiveSourceKind::Downwash;
        else
            return std::nullopt;
        consumed = true;
        return r;
    }
    if (e.kind == K::MouseButton && e.button == 0) {
        if (e.pressed) {
            mPressed = true;
            mShift = (e.mods & render::MOD_SHIFT) != 0;
            mPressX_px = e.x_px;
            mPressY_px = e.y_px;
            mMoved_px = 0.0;
            return std::nullopt;
        }
        if (!mPressed) return std::nullopt;
        mPressed = false;
        r.x_px = mPressX_px;
        r.y_px = mPressY_px;
        if (mShift) {
            r.kind = coupling::LiveSourceKind::GustFront;
            consumed = true;
            return r;
        }
        const double moved_px = std::hypot(e.x_px - mPressX_px, e.y_px - mPressY_px);
        if (moved_px < CLICK_SLOP_PX && mMoved_px < CLICK_SLOP_PX) {
            r.kind = coupling::LiveSourceKind::Whirlwind;
            return r;
        }
        return std::nullopt;
    }
    if (e.kind == K::MouseDrag && e.button == 0 && mPressed) {
        mMoved_px += std::hypot(e.dx, e.dy);
        consumed = mShift;  // a shift-drag draws the gust front, the camera stays
    }
    return std::nullopt;
}

}  // namespace gale::app
