// Mouse and keyboard: GLFW's callbacks, the camera, the tools (through Sculpting) and the
// shortcuts.

#include "app.hpp"

#include <algorithm>

#include "picking.hpp"
#include "shortcuts.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

static_assert(kKeyF1 == GLFW_KEY_F1);
static_assert('Z' == GLFW_KEY_Z && 'A' == GLFW_KEY_A && '0' == GLFW_KEY_0,
              "shortcuts.hpp and tool_palette.hpp write letter and digit keys as ASCII");

namespace {

App* app_of(GLFWwindow* w) {
    return static_cast<App*>(glfwGetWindowUserPointer(w));
}

// An exception must not cross GLFW (C code): each handler runs guarded, and an error in it is
// shown on the status line.
void on_button(GLFWwindow* w, int b, int action, int) {
    App* app = app_of(w);
    app->note_event();
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(w, &x, &y);
    const bool down = action == GLFW_PRESS;
    // A press on a panel is the panel's; a release always reaches the app, which ends
    // whatever the press began.
    if (down && app->ui_takes_pointer(x, y)) return;
    app->guarded("the tool stopped", [&] { app->mouse_button(b, down, x, y); });
}
void on_cursor(GLFWwindow* w, double x, double y) {
    App* app = app_of(w);
    app->note_event();
    app->guarded("the tool stopped", [&] { app->mouse_move(x, y); });
}
void on_wheel(GLFWwindow* w, double, double dy) {
    App* app = app_of(w);
    app->note_event();
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(w, &x, &y);
    if (app->ui_takes_pointer(x, y)) return;  // a panel scrolls
    app->scroll(dy);
}
void on_key(GLFWwindow* w, int key, int, int action, int mods) {
    App* app = app_of(w);
    app->note_event();
    // A held key repeats only the shortcuts that say so (undo and redo): a repeated Ctrl+N or
    // Ctrl+O would replace the document again for as long as the key stays down.
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    const Shortcut* shortcut = shortcut_for_key(key, ctrl);
    const bool repeats = shortcut != nullptr && shortcut->repeats;
    if (action != GLFW_PRESS && !(action == GLFW_REPEAT && repeats)) return;
    // Keys go to a text field being typed into (a path, a value typed into a slider). Not
    // WantCaptureKeyboard: ImGui decides that when a frame starts, and a key that follows the
    // click closing a prompt would find the prompt still there and be swallowed. The app
    // itself ignores shortcuts while a prompt waits (App::key).
    if (ImGui::GetIO().WantTextInput) return;
    app->guarded("the key's command failed", [&] { app->key(key, ctrl); });
}

// Events that only ImGui or the window itself act on still ask for a frame (typing into a
// field, focus, exposure, resizing): the loop's timed waits tell them from a plain timeout.
void on_char(GLFWwindow* w, unsigned int) {
    app_of(w)->note_event();
}
void on_focus(GLFWwindow* w, int) {
    app_of(w)->note_event();
}
void on_cursor_enter(GLFWwindow* w, int) {
    app_of(w)->note_event();
}
void on_refresh(GLFWwindow* w) {
    app_of(w)->note_event();
}
void on_framebuffer_size(GLFWwindow* w, int, int) {
    app_of(w)->note_event();
}
void on_iconify(GLFWwindow* w, int) {
    app_of(w)->note_event();
}
void on_drop(GLFWwindow* w, int count, const char** paths) {
    App* app = app_of(w);
    app->note_event();
    const std::vector<std::string> dropped(paths, paths + std::max(count, 0));
    app->guarded("the dropped file", [&] { app->drop_files(dropped); });
}

}  // namespace

void install_callbacks(GLFWwindow* window) {
    glfwSetMouseButtonCallback(window, on_button);
    glfwSetCursorPosCallback(window, on_cursor);
    glfwSetScrollCallback(window, on_wheel);
    glfwSetKeyCallback(window, on_key);
    glfwSetCharCallback(window, on_char);
    glfwSetWindowFocusCallback(window, on_focus);
    glfwSetCursorEnterCallback(window, on_cursor_enter);
    glfwSetWindowRefreshCallback(window, on_refresh);
    glfwSetFramebufferSizeCallback(window, on_framebuffer_size);
    glfwSetWindowIconifyCallback(window, on_iconify);
    glfwSetDropCallback(window, on_drop);
}

void App::note_event() {
    ++events_seen_;
    if (haptics_) haptics_->release();
    // ImGui settles over the frames after an event: a click that closes a prompt leaves it
    // open in the frame that handles the click, and until another frame is drawn ImGui still
    // says it wants the keyboard, so the next shortcut would be swallowed.
    redraw_frames_ = std::max(redraw_frames_, 3);
}

std::optional<Vec3> App::pick(double x, double y) const {
    int w = 0, h = 0;
    window_->window_size(w, h);
    const Ray ray = camera_.pixel_ray(x, y, w, h);
    const Rect d = doc_.tin().domain();
    const double step = std::max(d.width(), d.height()) / 2000.0;
    const auto hit = pick_terrain(doc_.tin(), ray, d.centre(), step, camera_.distance * 4.0);
    if (!hit) return std::nullopt;
    return hit->point;
}

void App::mouse_button(int button, bool down, double x, double y) {
    mouse_x_ = x;
    mouse_y_ = y;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        if (down) {
            left_down_ = true;
            hold_clock_ = Clock::now();
            // The previous edit's level closes, settled or not, even when this press misses.
            sculpting_.close_level(doc_);
            if (const auto p = pick(x, y)) sculpting_.press(doc_, *p, settings_);
        } else if (left_down_) {
            left_down_ = false;
            sculpting_.release(doc_, erosion_runs());
        }
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
        right_down_ = down;
    } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
        middle_down_ = down;
    }
}

void App::mouse_move(double x, double y) {
    const double dx = x - mouse_x_, dy = y - mouse_y_;
    mouse_x_ = x;
    mouse_y_ = y;
    if (right_down_) camera_.orbit(dx, dy);
    if (middle_down_) {
        int w = 0, h = 0;
        window_->window_size(w, h);
        camera_.pan(dx, dy, h);
    }
    cursor_ = pick(x, y);
    if (!left_down_ || !cursor_) return;
    // A press that missed the terrain starts the gesture where the drag first meets it.
    if (sculpting_.pressed())
        sculpting_.drag(doc_, *cursor_, settings_);
    else
        sculpting_.press(doc_, *cursor_, settings_);
}

void App::scroll(double dy) {
    camera_.zoom(dy);
}

void App::pick_tool(int index) {
    if (left_down_) return;  // not in the middle of a stroke
    settings_.tool = std::clamp(index, 0, kToolCount - 1);
}

void App::key(int k, bool ctrl) {
    // While a prompt waits for its answer, shortcuts must not change the document under it
    // (Ctrl+O could open another scene with the recovery prompt still about the first).
    if (prompt_open()) return;
    // While a job runs the keys wait for it, in order (Ctrl+S then Ctrl+Q typed during a save
    // quits once it is written), and act when it has ended; Escape cancels it, as its Cancel
    // button does, and the keys typed meanwhile with it.
    if (busy()) {
        if (k == GLFW_KEY_ESCAPE)
            cancel_job();
        else if (keys_after_job_.size() < kKeysAfterJob)
            keys_after_job_.push_back({k, ctrl});
        return;
    }
    if (const Shortcut* shortcut = shortcut_for_key(k, ctrl)) {
        run_command(shortcut->command);
    } else if (ctrl) {
        return;  // no tool key uses Ctrl: Ctrl+R must not pick the Raise brush
    } else if (const std::optional<int> tool = tool_for_key(k)) {
        pick_tool(*tool);
    }
}

void App::run_command(Command command) {
    switch (command) {
        case Command::Undo:
            undo();
            break;
        case Command::Redo:
            redo();
            break;
        case Command::Save:
            request_save(save_path());
            break;
        case Command::New:
            replace_document("New", [this] { new_document(); });
            break;
        case Command::Open:
            replace_document("Open", [this] { open_reporting(path_buf_); });
            break;
        case Command::Quit:
            // As the window's close button: an untitled scene's unsaved edits are asked about.
            glfwSetWindowShouldClose(window_->glfw(), GLFW_TRUE);
            break;
        case Command::Frame:
            frame_terrain();
            break;
        case Command::Help:
            help_open_ = !help_open_;
            break;
    }
}

}  // namespace sandtin::editor
