/// \file GlfwWindow.cpp
/// The windowed GlContext (see GlfwWindow.h).

#include "render/GlfwWindow.h"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <cstring>
#include <mutex>

#include "render/GlInfo.h"

namespace gale::render {
namespace {

std::string lastGlfwError() {
    const char* text = nullptr;
    const int code = glfwGetError(&text);
    if (code == GLFW_NO_ERROR) return "no GLFW error reported";
    return text ? std::string(text) : "GLFW error " + std::to_string(code);
}

GLFWwindow* handle(void* w) { return static_cast<GLFWwindow*>(w); }

Key keyFromGlfw(int key) {
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return Key(int(Key::A) + (key - GLFW_KEY_A));
    switch (key) {
        case GLFW_KEY_SPACE:
            return Key::Space;
        case GLFW_KEY_ESCAPE:
            return Key::Escape;
        case GLFW_KEY_RIGHT:
            return Key::Right;
        case GLFW_KEY_LEFT:
            return Key::Left;
        case GLFW_KEY_UP:
            return Key::Up;
        case GLFW_KEY_DOWN:
            return Key::Down;
        case GLFW_KEY_EQUAL:
            return Key::Equal;
        case GLFW_KEY_MINUS:
            return Key::Minus;
        case GLFW_KEY_KP_ADD:
            return Key::KeypadAdd;
        case GLFW_KEY_KP_SUBTRACT:
            return Key::KeypadSubtract;
        case GLFW_KEY_LEFT_BRACKET:
            return Key::LeftBracket;
        case GLFW_KEY_RIGHT_BRACKET:
            return Key::RightBracket;
        default:
            return Key::Unknown;
    }
}

int modsFromGlfw(int mods) {
    return ((mods & GLFW_MOD_SHIFT) ? MOD_SHIFT : 0) |
           ((mods & GLFW_MOD_CONTROL) ? MOD_CONTROL : 0) | ((mods & GLFW_MOD_ALT) ? MOD_ALT : 0);
}

int heldMods(GLFWwindow* w) {
    int mods = 0;
    if (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
        glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS)
        mods |= MOD_SHIFT;
    if (glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
        glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS)
        mods |= MOD_CONTROL;
    if (glfwGetKey(w, GLFW_KEY_LEFT_ALT) == GLFW_PRESS ||
        glfwGetKey(w, GLFW_KEY_RIGHT_ALT) == GLFW_PRESS)
        mods |= MOD_ALT;
    return mods;
}

// GLFW is process-global: initialise once, terminate at exit.
void initGlfwOnce() {
    static std::once_flag once;
    static bool ok = false;
    static std::string error;
    std::call_once(once, [] {
        const char* display = std::getenv("DISPLAY");
        if (display == nullptr || *display == '\0') {
            error = "no display (DISPLAY is not set): use `gale render` for headless frames";
            return;
        }
        if (!glfwInit()) {
            error = "cannot open the display '" + std::string(display) + "' (" + lastGlfwError() +
                    "): use `gale render` for headless frames";
            return;
        }
        std::atexit(glfwTerminate);
        ok = true;
    });
    if (!ok) throw NoDisplayError(error);
}

}  // namespace

struct GlfwWindow::Callbacks {
    static GlfwWindow* self(GLFWwindow* w) {
        return static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w));
    }
    static void key(GLFWwindow* w, int key, int, int action, int mods) {
        if (action == GLFW_RELEASE) return;
        InputEvent e;
        e.kind = InputEvent::Kind::Key;
        e.key = keyFromGlfw(key);
        e.mods = modsFromGlfw(mods);
        self(w)->push(e);
    }
    static void button(GLFWwindow* w, int button, int action, int mods) {
        if (button > 2) return;
        InputEvent e;
        e.kind = InputEvent::Kind::MouseButton;
        e.button = button;
        e.pressed = action == GLFW_PRESS;
        e.mods = modsFromGlfw(mods);
        self(w)->push(e);
    }
    static void cursor(GLFWwindow* w, double x, double y) {
        GlfwWindow* s = self(w);
        if (s->mHaveCursor) {
            for (int button = 0; button < 3; ++button) {
                if (glfwGetMouseButton(w, button) == GLFW_PRESS) {
                    InputEvent e;
                    e.kind = InputEvent::Kind::MouseDrag;
                    e.button = button;
                    e.mods = heldMods(w);
                    e.dx = x - s->mLastX;
                    e.dy = y - s->mLastY;
                    e.x_px = x;
                    e.y_px = y;
                    s->mPending.push_back(e);
                    break;
                }
            }
        }
        s->mLastX = x;
        s->mLastY = y;
        s->mHaveCursor = true;
    }
    static void scroll(GLFWwindow* w, double dx, double dy) {
        InputEvent e;
        e.kind = InputEvent::Kind::Scroll;
        e.dx = dx;
        e.dy = dy;
        self(w)->push(e);
    }
    static void close(GLFWwindow* w) {
        InputEvent e;
        e.kind = InputEvent::Kind::Close;
        self(w)->push(e);
    }
};

std::unique_ptr<GlfwWindow> GlfwWindow::open(int width, int height, const std::string& title) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw std::runtime_error("window size must be 1..16384 per side, got " +
                                 std::to_string(width) + "x" + std::to_string(height));
    initGlfwOnce();
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_OSMESA_CONTEXT_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (w == nullptr)
        throw std::runtime_error(
            "cannot open a " + std::to_string(width) + "x" + std::to_string(height) +
            " window with an OpenGL 4.5 core context through OSMesa: " + lastGlfwError());
    std::unique_ptr<GlfwWindow> window(new GlfwWindow(w, width, height));
    glfwSetWindowUserPointer(w, window.get());
    glfwSetKeyCallback(w, &Callbacks::key);
    glfwSetCursorPosCallback(w, &Callbacks::cursor);
    glfwSetMouseButtonCallback(w, &Callbacks::button);
    glfwSetScrollCallback(w, &Callbacks::scroll);
    glfwSetWindowCloseCallback(w, &Callbacks::close);
    window->makeCurrent();
    glfwSwapInterval(0);
    return window;
}

Key letterKey(char c) {
    if (c >= 'a' && c <= 'z') return Key(int(Key::A) + (c - 'a'));
    if (c >= 'A' && c <= 'Z') return Key(int(Key::A) + (c - 'A'));
    return Key::Unknown;
}

void GlfwWindow::push(InputEvent e) {
    e.x_px = mLastX;
    e.y_px = mLastY;
    mPending.push_back(e);
}

GlfwWindow::GlfwWindow(void* window, int width, int height)
    : mWindow(window), mWidth(width), mHeight(height) {}

GlfwWindow::~GlfwWindow() {
    if (mWindow != nullptr) glfwDestroyWindow(handle(mWindow));
}

void GlfwWindow::makeCurrent() { glfwMakeContextCurrent(handle(mWindow)); }

void GlfwWindow::readPixels(Image& out) {
    makeCurrent();
    glFinish();
    out.width = mWidth;
    out.height = mHeight;
    out.rgba.resize(static_cast<size_t>(mWidth) * mHeight * 4);
    std::vector<uint8_t> bottomUp(out.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, mWidth, mHeight, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    const size_t rowBytes = static_cast<size_t>(mWidth) * 4;
    for (int y = 0; y < mHeight; ++y)
        std::memcpy(out.rgba.data() + y * rowBytes, bottomUp.data() + (mHeight - 1 - y) * rowBytes,
                    rowBytes);
}

void GlfwWindow::present() { glfwSwapBuffers(handle(mWindow)); }

std::string GlfwWindow::description() const {
    const GlInfo info = queryGlInfo();
    return info.renderer + ", " + info.version + ", in a GLFW window";
}

std::vector<InputEvent> GlfwWindow::pollEvents() {
    glfwPollEvents();
    std::vector<InputEvent> events;
    events.swap(mPending);
    return events;
}

bool GlfwWindow::closeRequested() const { return glfwWindowShouldClose(handle(mWindow)); }

void GlfwWindow::setTitle(const std::string& title) {
    glfwSetWindowTitle(handle(mWindow), title.c_str());
}

}  // namespace gale::render
