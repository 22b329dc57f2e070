#include "x_input.hpp"

#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3.h>
#include <GLFW/glfw3native.h>
#include <X11/XKBlib.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XTest.h>
#include <X11/keysym.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace sandtin::editor {

struct XInput::State {
    GLFWwindow* window = nullptr;
    Display* display = nullptr;
    Window x_window = 0;
    bool restore_auto_repeat = false;
};

namespace {

/// The X keysym of a GLFW key; 0 when there is none here. GLFW's printable keys are their
/// ASCII upper-case codes, which are X's keysyms for the unshifted key in lower case.
KeySym keysym_of(int key) {
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z)
        return static_cast<KeySym>(XK_a + (key - GLFW_KEY_A));
    if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9)
        return static_cast<KeySym>(XK_0 + (key - GLFW_KEY_0));
    switch (key) {
        case GLFW_KEY_SPACE:
            return XK_space;
        case GLFW_KEY_MINUS:
            return XK_minus;
        case GLFW_KEY_PERIOD:
            return XK_period;
        case GLFW_KEY_ENTER:
            return XK_Return;
        case GLFW_KEY_ESCAPE:
            return XK_Escape;
        case GLFW_KEY_BACKSPACE:
            return XK_BackSpace;
        case GLFW_KEY_DELETE:
            return XK_Delete;
        case GLFW_KEY_TAB:
            return XK_Tab;
        case GLFW_KEY_LEFT:
            return XK_Left;
        case GLFW_KEY_RIGHT:
            return XK_Right;
        case GLFW_KEY_UP:
            return XK_Up;
        case GLFW_KEY_DOWN:
            return XK_Down;
        case GLFW_KEY_HOME:
            return XK_Home;
        case GLFW_KEY_END:
            return XK_End;
        case GLFW_KEY_LEFT_CONTROL:
            return XK_Control_L;
        case GLFW_KEY_LEFT_SHIFT:
            return XK_Shift_L;
        case GLFW_KEY_F1:
            return XK_F1;
        default:
            return 0;
    }
}

unsigned int x_button_of(int glfw_button) {
    switch (glfw_button) {
        case GLFW_MOUSE_BUTTON_LEFT:
            return 1;
        case GLFW_MOUSE_BUTTON_MIDDLE:
            return 2;
        case GLFW_MOUSE_BUTTON_RIGHT:
            return 3;
        default:
            throw std::runtime_error("no X button for GLFW mouse button " +
                                     std::to_string(glfw_button));
    }
}

}  // namespace

XInput::XInput(GLFWwindow* window) : x_(std::make_unique<State>()) {
    x_->window = window;
    x_->display = glfwGetX11Display();
    if (x_->display == nullptr)
        throw std::runtime_error("scripted input needs an X server (run under xvfb-run)");
    int event_base = 0, error_base = 0, major = 0, minor = 0;
    if (!XTestQueryExtension(x_->display, &event_base, &error_base, &major, &minor))
        throw std::runtime_error("scripted input needs the X server's XTEST extension");
    x_->x_window = glfwGetX11Window(window);
    // A key a step holds down is released one frame later, and a frame can take longer than
    // the server's auto-repeat delay on a loaded machine: repeats would then arrive or not
    // with the machine's speed. Off while this runs (the server's setting, so it is restored).
    XKeyboardState keyboard{};
    XGetKeyboardControl(x_->display, &keyboard);
    if (keyboard.global_auto_repeat == AutoRepeatModeOn) {
        XAutoRepeatOff(x_->display);
        x_->restore_auto_repeat = true;
    }
    // Keys go to the focused window; without a window manager (Xvfb) nothing else gives it
    // the focus.
    glfwFocusWindow(window);
    sync();
}

XInput::~XInput() {
    // Auto-repeat is the server's setting, not this client's: restored while the connection
    // lives (the owner destroys this before glfwTerminate).
    if (x_->restore_auto_repeat) {
        XAutoRepeatOn(x_->display);
        XFlush(x_->display);
    }
}

void XInput::move_to(double x, double y) {
    // XTest moves the pointer in root coordinates: where the window's origin is on the screen.
    Window child = 0;
    int root_x = 0, root_y = 0;
    XTranslateCoordinates(x_->display, x_->x_window, DefaultRootWindow(x_->display), 0, 0, &root_x,
                          &root_y, &child);
    // Screen coordinates and framebuffer pixels agree on X11 (no content scaling of the
    // cursor position there).
    XTestFakeMotionEvent(x_->display, -1, root_x + static_cast<int>(std::lround(x)),
                         root_y + static_cast<int>(std::lround(y)), CurrentTime);
}

void XInput::button(int glfw_button, bool down) {
    XTestFakeButtonEvent(x_->display, x_button_of(glfw_button), down ? True : False, CurrentTime);
}

void XInput::wheel(bool up) {
    const unsigned int b = up ? 4 : 5;  // X's wheel buttons, which GLFW reports as scrolling
    XTestFakeButtonEvent(x_->display, b, True, CurrentTime);
    XTestFakeButtonEvent(x_->display, b, False, CurrentTime);
}

void XInput::key(int glfw_key, bool down) {
    const KeySym sym = keysym_of(glfw_key);
    const KeyCode code = sym == 0 ? 0 : XKeysymToKeycode(x_->display, sym);
    if (code == 0)
        throw std::runtime_error("scripted input has no X key for GLFW key " +
                                 std::to_string(glfw_key));
    XTestFakeKeyEvent(x_->display, code, down ? True : False, CurrentTime);
}

void XInput::type(char c) {
    if (c < 0x20 || c > 0x7e)
        throw std::runtime_error("scripted typing takes printable ASCII, not code " +
                                 std::to_string(static_cast<int>(c)));
    // Printable ASCII codes are their own keysyms.
    const KeySym sym = static_cast<KeySym>(static_cast<unsigned char>(c));
    const KeyCode code = XKeysymToKeycode(x_->display, sym);
    if (code == 0)
        throw std::runtime_error(std::string("the X keyboard has no key for '") + c + "'");
    // The shifted symbol of its key needs Shift held.
    const bool shift = XkbKeycodeToKeysym(x_->display, code, 0, 0) != sym;
    const KeyCode shift_code = XKeysymToKeycode(x_->display, XK_Shift_L);
    if (shift) XTestFakeKeyEvent(x_->display, shift_code, True, CurrentTime);
    XTestFakeKeyEvent(x_->display, code, True, CurrentTime);
    XTestFakeKeyEvent(x_->display, code, False, CurrentTime);
    if (shift) XTestFakeKeyEvent(x_->display, shift_code, False, CurrentTime);
}

void XInput::request_close() {
    XEvent e{};
    e.xclient.type = ClientMessage;
    e.xclient.window = x_->x_window;
    e.xclient.message_type = XInternAtom(x_->display, "WM_PROTOCOLS", False);
    e.xclient.format = 32;
    e.xclient.data.l[0] = static_cast<long>(XInternAtom(x_->display, "WM_DELETE_WINDOW", False));
    e.xclient.data.l[1] = CurrentTime;
    XSendEvent(x_->display, x_->x_window, False, NoEventMask, &e);
}

void XInput::sync() {
    XSync(x_->display, False);
}

}  // namespace sandtin::editor
