// The interactive editor (no script at all) driven by xdotool on a private X server, as a
// person at the mouse and keyboard: the three prompts that once crashed it (Recover, Discard and
// New, Save and New). xdotool's events come from outside the process, through the X server,
// GLFW and ImGui, exactly as a hand's. The test aims at controls through the editor's
// --widget-map file, and reads what the editor did from the scenes it saved.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "editor_harness.hpp"
#include "io/autosave.hpp"
#include "io/session_file.hpp"
#include "tin/tin.hpp"
#include "tin/tin_snapshot.hpp"

namespace sandtin {
namespace {

using namespace editor_test;
using namespace std::chrono_literals;

bool have_xdotool() {
    return std::system("command -v xdotool > /dev/null 2>&1 && command -v Xvfb > /dev/null 2>&1") ==
           0;
}

/// Starts `argv` in `dir` with extra environment entries; returns its pid.
pid_t spawn(const std::vector<std::string>& argv, const fs::path& dir,
            const std::vector<std::string>& env, const fs::path& log) {
    const pid_t pid = fork();
    if (pid != 0) return pid;
    if (chdir(dir.c_str()) != 0) _exit(126);
    for (const std::string& e : env)
        putenv(const_cast<char*>(e.c_str()));
    const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out >= 0) {
        dup2(out, 1);
        dup2(out, 2);
    }
    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    _exit(127);
}

/// A private X server: the server picks a free display itself (-displayfd), so parallel tests
/// never share one.
class XServer {
  public:
    XServer() {
        int fds[2];
        if (pipe(fds) != 0) return;
        pid_ = fork();
        if (pid_ == 0) {
            close(fds[0]);
            const std::string fd = std::to_string(fds[1]);
            execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1600x24",
                   "-nolisten", "tcp", static_cast<char*>(nullptr));
            _exit(127);
        }
        close(fds[1]);
        char text[16] = {};
        std::size_t got = 0;
        while (got + 1 < sizeof(text)) {
            const ssize_t n = read(fds[0], text + got, sizeof(text) - 1 - got);
            if (n <= 0) break;
            got += static_cast<std::size_t>(n);
            if (text[got - 1] == '\n') break;
        }
        close(fds[0]);
        if (got > 0) display_ = ":" + std::string(text, text + got - 1);
    }
    ~XServer() {
        if (pid_ > 0) {
            kill(pid_, SIGTERM);
            waitpid(pid_, nullptr, 0);
        }
    }
    XServer(const XServer&) = delete;
    XServer& operator=(const XServer&) = delete;
    const std::string& display() const { return display_; }

  private:
    pid_t pid_ = -1;
    std::string display_;
};

/// The interactive editor on a private X server, and xdotool to drive it.
class LiveEditor {
  public:
    explicit LiveEditor(const std::string& name) {
        dir_ = kWork / ("xdotool-" + name);
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        map_ = dir_ / "widgets.json";
    }
    /// Starts the editor, in this session's folder (where an untitled scene's Save writes
    /// scene.sandtin), with `args` after the test's own.
    void start(const std::vector<std::string>& args) {
        std::vector<std::string> argv = {SANDTIN_EDITOR_BINARY, "--validation",
                                         "--settings",          (dir_ / "settings.json").string(),
                                         "--widget-map",        map_.string()};
        argv.insert(argv.end(), args.begin(), args.end());
        pid_ = spawn(argv, dir_, {"DISPLAY=" + x_.display()}, dir_ / "editor.log");
    }
    ~LiveEditor() {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
    }
    LiveEditor(const LiveEditor&) = delete;
    LiveEditor& operator=(const LiveEditor&) = delete;

    const fs::path& dir() const { return dir_; }

    /// Runs xdotool with `args` against this session's server.
    void xdotool(const std::string& args) const {
        const std::string cmd = "DISPLAY=" + x_.display() + " xdotool " + args;
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
    /// The centre of `widget` in window pixels, once the editor has drawn it (up to `wait`).
    std::optional<std::pair<int, int>> widget(const std::string& name,
                                              std::chrono::seconds wait = 60s) const {
        const auto until = std::chrono::steady_clock::now() + wait;
        while (std::chrono::steady_clock::now() < until) {
            std::ifstream in(map_);
            try {
                const nlohmann::json j = nlohmann::json::parse(in);
                if (j.contains(name)) {
                    const auto& r = j.at(name);
                    return std::pair<int, int>{
                        static_cast<int>(0.5 * (r[0].get<double>() + r[2].get<double>())),
                        static_cast<int>(0.5 * (r[1].get<double>() + r[3].get<double>()))};
                }
            } catch (const std::exception&) {
                // Not written yet.
            }
            std::this_thread::sleep_for(100ms);
        }
        return std::nullopt;
    }
    /// A hand's click on the control: the pointer over it first, then the button, held a
    /// moment. A prompt's button is clicked once the prompt has settled where it shows, and the
    /// click is done once the prompt is gone (an editor busy with what the click asked for
    /// takes no shortcuts while a prompt is open, as with a hand).
    void click(const std::string& name) const {
        const bool prompt = name.find('/') != std::string::npos;
        if (prompt) widget(name);
        if (prompt) std::this_thread::sleep_for(500ms);  // a popup places itself in 2 frames
        const auto at = widget(name);
        ASSERT_TRUE(at) << "no '" << name << "' on screen: " << log();
        move(at->first, at->second);
        press_and_release();
        if (prompt) {
            // ImGui sees a press and its release only in different frames; on a machine so
            // loaded that one frame outlasts the hold, the click is lost, and a hand clicks
            // again. A prompt button's second click cannot act twice: the prompt is gone.
            if (!gone(name, 15s)) press_and_release();
            EXPECT_TRUE(gone(name)) << "the prompt of '" << name << "' stayed: " << log();
        } else {
            std::this_thread::sleep_for(500ms);
        }
    }
    /// The left button down and, a few frames later, up.
    void press_and_release() const {
        xdotool("mousedown 1");
        std::this_thread::sleep_for(400ms);
        xdotool("mouseup 1");
    }
    /// Waits until long work the last action started (New, Open, Recover, Save: a worker under
    /// the bar) has ended, as a hand waits for the bar to go before it goes on.
    void wait_for_job() const { EXPECT_TRUE(gone("job")) << "the job never ended: " << log(); }
    /// Waits until `name` is no longer on screen.
    bool gone(const std::string& name, std::chrono::seconds wait = 60s) const {
        const auto until = std::chrono::steady_clock::now() + wait;
        while (std::chrono::steady_clock::now() < until) {
            std::ifstream in(map_);
            try {
                if (!nlohmann::json::parse(in).contains(name)) return true;
            } catch (const std::exception&) {
                // Being written.
            }
            std::this_thread::sleep_for(100ms);
        }
        return false;
    }
    void move(int x, int y) const {
        xdotool("mousemove --window " + window() + " " + std::to_string(x) + " " +
                std::to_string(y));
        std::this_thread::sleep_for(300ms);  // a frame or two with the pointer there
    }
    /// A left-button drag across the terrain, in steps.
    void drag(int x0, int y0, int x1, int y1) const {
        move(x0, y0);
        xdotool("mousedown 1");
        std::this_thread::sleep_for(200ms);
        for (int k = 1; k <= 8; ++k) {
            xdotool("mousemove --window " + window() + " " +
                    std::to_string(x0 + (x1 - x0) * k / 8) + " " +
                    std::to_string(y0 + (y1 - y0) * k / 8));
            std::this_thread::sleep_for(100ms);
        }
        xdotool("mouseup 1");
        std::this_thread::sleep_for(1s);
    }
    void key(const std::string& keys) const {
        xdotool("key --window " + window() + " " + keys);
        std::this_thread::sleep_for(500ms);
    }
    /// Waits for the editor to exit; its exit code, or -1 if it had to be killed, or the
    /// signal that ended it as 128 + signal.
    int wait_exit(std::chrono::seconds at_most = 60s) {
        const auto until = std::chrono::steady_clock::now() + at_most;
        while (std::chrono::steady_clock::now() < until) {
            int status = 0;
            if (waitpid(pid_, &status, WNOHANG) == pid_) {
                pid_ = -1;
                if (WIFEXITED(status)) return WEXITSTATUS(status);
                return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
            }
            std::this_thread::sleep_for(100ms);
        }
        return -1;
    }
    std::string log() const {
        std::ifstream in(dir_ / "editor.log");
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

  private:
    std::string window() const {
        if (window_.empty()) {
            const std::string cmd = "DISPLAY=" + x_.display() +
                                    " xdotool search --sync --onlyvisible --name '^sandtin$'";
            FILE* p = popen(cmd.c_str(), "r");
            char line[64] = {};
            if (p != nullptr && std::fgets(line, sizeof(line), p) != nullptr)
                window_ = std::to_string(std::strtoul(line, nullptr, 10));
            if (p != nullptr) pclose(p);
        }
        return window_;
    }

    XServer x_;
    fs::path dir_, map_;
    pid_t pid_ = -1;
    mutable std::string window_;
};

class EditorXdotool : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!have_xdotool()) GTEST_SKIP() << "xdotool or Xvfb is not installed";
    }
};

// The terrain's middle in a 1280 x 720 window (right of the panel).
constexpr int kX0 = 640, kX1 = 900, kY = 380;

TEST_F(EditorXdotool, TheThreePromptsAnsweredWithTheMouse) {
    const fs::path base = kWork / "xdotool-base.sandtin";
    ASSERT_EQ(run_editor("xdotool-base", kFlat, "--save-after " + base.string()).exit_code, 0);
    const Tin sandbox = Tin::from_snapshot(load_session(base).terrain);

    {
        // Recover: an autosave newer than the scene, with one vertex raised by 3 cm. Recover,
        // a stroke, Ctrl+S, Ctrl+Q: the scene holds both.
        LiveEditor s("recover");
        const fs::path scene = s.dir() / "scene.sandtin";
        fs::copy_file(base, scene);
        const auto [edited, raised] = write_autosave_raising_a_vertex(scene, 0.03);
        s.start({scene.string()});
        s.click("recovery/Recover");
        s.wait_for_job();
        s.drag(kX0, kY, kX1, kY);
        s.key("ctrl+s");
        s.key("ctrl+q");
        ASSERT_EQ(s.wait_exit(), 0) << s.log();
        const Session saved = load_session(scene);
        const Tin t = Tin::from_snapshot(saved.terrain);
        EXPECT_NEAR(*t.height_at(edited.terrain.vertices.position[raised]),
                    edited.terrain.vertices.height[raised], 1e-9);
        EXPECT_GT(surface_difference(t, Tin::from_snapshot(edited.terrain)), 0.005)
            << "the stroke after the recovery was not saved";
    }
    {
        // An untitled sandbox, a stroke, New, "Discard and New", Ctrl+S, Ctrl+Q: the saved
        // scene is a new sandbox.
        LiveEditor s("discard");
        s.start({});
        s.widget("New");
        s.drag(kX0, kY, kX1, kY);
        s.click("New");
        s.click("unsaved/Discard");
        s.wait_for_job();
        s.key("ctrl+s");
        s.key("ctrl+q");
        ASSERT_EQ(s.wait_exit(), 0) << s.log();
        const fs::path saved = s.dir() / "scene.sandtin";
        ASSERT_TRUE(fs::exists(saved)) << s.log();
        EXPECT_LT(surface_difference(Tin::from_snapshot(load_session(saved).terrain), sandbox),
                  1e-12);
    }
    {
        // The same, "Save and New": the stroke is saved, and the new sandbox has nothing to
        // save, so Ctrl+Q quits at once.
        LiveEditor s("save");
        s.start({});
        s.widget("New");
        s.drag(kX0, kY, kX1, kY);
        s.click("New");
        s.click("unsaved/Save");
        s.key("ctrl+q");
        ASSERT_EQ(s.wait_exit(), 0) << s.log();
        const fs::path saved = s.dir() / "scene.sandtin";
        ASSERT_TRUE(fs::exists(saved)) << s.log();
        EXPECT_GT(surface_difference(Tin::from_snapshot(load_session(saved).terrain), sandbox),
                  0.005);
    }
}

}  // namespace
}  // namespace sandtin
