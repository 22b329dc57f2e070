#pragma once
// Real input for scripted runs: mouse and keyboard events sent through the X server (its XTEST
// extension, as xdotool sends them), so they arrive in GLFW's event queue, its callbacks and
// ImGui's input exactly as a hand on a mouse and keyboard makes them. A scripted click on a
// button therefore clicks the button, a click over a panel does not reach the terrain behind
// it, and a hover shows the tooltip.
//
// Every call queues its events; sync() waits until the server has turned them into events in
// this client's queue (the X protocol delivers events before a later reply), so the next
// glfwPollEvents() sees all of them, in order.

#include <memory>

struct GLFWwindow;

namespace sandtin::editor {

class XInput {
  public:
    /// Throws std::runtime_error naming the problem when the window is not on an X server
    /// or the server lacks XTEST (a scripted run then cannot drive real input).
    /// Turns the server's key auto-repeat off while it lives (a step's key is released a frame
    /// later, and repeats would come or not with the machine's speed). Destroy it before
    /// glfwTerminate(), which closes the connection it uses.
    explicit XInput(GLFWwindow* window);
    ~XInput();
    XInput(const XInput&) = delete;
    XInput& operator=(const XInput&) = delete;

    /// The pointer to (x, y), in the window's screen coordinates (what glfwGetCursorPos says).
    void move_to(double x, double y);
    /// A GLFW mouse button (GLFW_MOUSE_BUTTON_LEFT, ...) pressed or released.
    void button(int glfw_button, bool down);
    /// One wheel click: up (away from the user, GLFW's +1) or down.
    void wheel(bool up);
    /// A GLFW key (GLFW_KEY_A, GLFW_KEY_ENTER, GLFW_KEY_LEFT_CONTROL, ...) pressed or released.
    /// Throws for a key this injector has no X key for.
    void key(int glfw_key, bool down);
    /// Types one printable ASCII character (with Shift when the layout needs it): its press and
    /// release. ImGui queues characters, so both may fall in one frame.
    void type(char c);
    /// The window manager's close request (WM_DELETE_WINDOW), as a title bar's close button
    /// sends it.
    void request_close();
    /// Waits until the server has delivered every event queued so far.
    void sync();

  private:
    struct State;
    std::unique_ptr<State> x_;
};

}  // namespace sandtin::editor
