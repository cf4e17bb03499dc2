#pragma once
/// \file GlfwWindow.h
/// A GlContext in a GLFW window. The context is made through OSMesa
/// (GLFW_CONTEXT_CREATION_API = GLFW_OSMESA_CONTEXT_API), so the window and headless runs draw with
/// the same GL implementation and give the same pixels (docs/design.md 7); GLFW copies each
/// finished frame to the X window. GLFW 3.3 still needs an X display for that.

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/GlContext.h"

namespace gale::render {

/// Thrown when no window can be opened because there is no display; the message says to use
/// `gale render` instead.
class NoDisplayError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// The keys the viewer answers, the window's own names for them (GLFW's codes stay inside
/// GlfwWindow.cpp). Letters A..Z are contiguous, so Key(int(Key::A) + (c - 'A')) names letter c.
enum class Key {
    Unknown,
    A,
    B,
    C,
    D,
    E,
    F,
    G,
    H,
    I,
    J,
    K,
    L,
    M,
    N,
    O,
    P,
    Q,
    R,
    S,
    T,
    U,
    V,
    W,
    X,
    Y,
    Z,
    Space,
    Escape,
    Right,
    Left,
    Up,
    Down,
    Equal,  ///< '=' (with '+' on the same key on most layouts)
    Minus,
    KeypadAdd,
    KeypadSubtract,
    LeftBracket,
    RightBracket,
};

/// The letter key for 'A'..'Z' or 'a'..'z'; Key::Unknown for any other character.
Key letterKey(char c);

/// Modifier bits of an InputEvent.
enum KeyMods : int { MOD_NONE = 0, MOD_SHIFT = 1, MOD_CONTROL = 2, MOD_ALT = 4 };

/// One input event, in window pixels (origin top-left).
struct InputEvent {
    enum class Kind { Key, MouseButton, MouseDrag, Scroll, Close };
    Kind kind = Kind::Key;
    Key key = Key::Unknown;  ///< Kind::Key, on press and repeat
    int mods = MOD_NONE;     ///< KeyMods bits held (Key, MouseButton, MouseDrag)
    int button = 0;          ///< mouse button (0 left, 1 right, 2 middle): MouseButton, MouseDrag
    bool pressed = false;    ///< MouseButton: true on press, false on release
    double x_px = 0.0;       ///< cursor position when the event happened (every kind)
    double y_px = 0.0;
    double dx = 0.0;  ///< drag delta x in pixels, or scroll x offset
    double dy = 0.0;  ///< drag delta y in pixels, or scroll y offset
};

class GlfwWindow : public GlContext {
  public:
    /// Opens a width x height window (not resizable) with a 4.5 core context made through OSMesa.
    /// Throws NoDisplayError without a display, std::runtime_error for any other failure.
    static std::unique_ptr<GlfwWindow> open(int width, int height, const std::string& title);
    ~GlfwWindow() override;

    void makeCurrent() override;
    int width() const override { return mWidth; }
    int height() const override { return mHeight; }
    void readPixels(Image& out) override;
    /// Shows the frame in the window (GLFW copies the OSMesa buffer to X).
    void present() override;
    std::string description() const override;

    /// Processes window events without blocking; returns them in order.
    std::vector<InputEvent> pollEvents();
    /// True once the user asked to close the window.
    bool closeRequested() const;
    void setTitle(const std::string& title);

  private:
    GlfwWindow(void* window, int width, int height);
    struct Callbacks;
    void push(InputEvent e);  ///< queues e at the last cursor position
    void* mWindow;  // GLFWwindow*, kept out of this header so GLFW stays private to render/
    int mWidth, mHeight;
    std::vector<InputEvent> mPending;
    double mLastX = 0.0, mLastY = 0.0;
    bool mHaveCursor = false;
};

}  // namespace gale::render
