#include "native_file_dialog.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

extern char** environ;

namespace sandtin::editor {

namespace fs = std::filesystem;

namespace {

/// `name` as an executable file in one of `search_path`'s folders.
std::optional<fs::path> on_path(std::string_view search_path, const char* name) {
    std::size_t begin = 0;
    while (begin <= search_path.size()) {
        std::size_t end = search_path.find(':', begin);
        if (end == std::string_view::npos) end = search_path.size();
        // An empty entry is the current folder, as for a shell.
        const std::string folder(search_path.substr(begin, end - begin));
        const fs::path candidate = fs::path(folder.empty() ? "." : folder) / name;
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
        begin = end + 1;
    }
    return std::nullopt;
}

/// "*.sandtin *.SANDTIN": zenity's and kdialog's patterns are matched case and all.
std::string patterns(const FileFilter& f) {
    if (f.extensions.empty()) return "*";
    std::string text;
    for (const std::string& e : f.extensions) {
        std::string upper = e;
        for (char& c : upper)
            c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        text += (text.empty() ? "*" : " *") + e + " *" + upper;
    }
    return text;
}

/// Where the dialog starts: the folder, with the proposed name when saving.
std::string start_at(const FileDialogRequest& r) {
    if (r.saving && !r.name.empty()) return (r.folder / r.name).string();
    std::string folder = r.folder.string();
    if (folder.empty() || folder.back() != '/') folder += '/';  // zenity: a folder, not a file
    return folder;
}

/// A pipe whose ends close on exec (the child gets only the copies dup2 makes).
std::array<int, 2> make_pipe() {
    std::array<int, 2> fds{-1, -1};
    if (::pipe2(fds.data(), O_CLOEXEC) != 0)
        throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    return fds;
}

/// The last line of `text` with words, for an error message.
std::string last_line(const std::string& text) {
    std::size_t end = text.find_last_not_of("\r\n \t");
    if (end == std::string::npos) return {};
    const std::size_t begin = text.rfind('\n', end);
    return text.substr(begin == std::string::npos ? 0 : begin + 1,
                       end - (begin == std::string::npos ? 0 : begin + 1) + 1);
}

NativeDialogResult failed(std::string why) {
    NativeDialogResult r;
    r.outcome = NativeDialogResult::Outcome::Failed;
    r.error = std::move(why);
    return r;
}

/// Reads the child's stdout and stderr until both close or `stop`; true when stopped.
bool read_until_closed(std::array<int, 2> fds, std::array<std::string*, 2> into,
                       const std::atomic<bool>& stop) {
    std::array<pollfd, 2> p{pollfd{fds[0], POLLIN, 0}, pollfd{fds[1], POLLIN, 0}};
    while (p[0].fd >= 0 || p[1].fd >= 0) {
        if (stop) return true;
        // A tenth of a second at most between looks at `stop`.
        const int n = ::poll(p.data(), p.size(), 100);
        if (n < 0 && errno != EINTR) return false;
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (p[i].fd < 0 || (p[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
            char buffer[4096];
            const ssize_t got = ::read(p[i].fd, buffer, sizeof(buffer));
            if (got > 0) {
                into[i]->append(buffer, static_cast<std::size_t>(got));
            } else if (got == 0 || errno != EINTR) {
                p[i].fd = -1;  // closed (the caller closes the descriptor)
            }
        }
    }
    return false;
}

}  // namespace

std::optional<DialogProgram> find_dialog_program(std::string_view search_path,
                                                 std::string_view desktop) {
    const bool kde = desktop.find("KDE") != std::string_view::npos;
    const std::pair<DialogProgram::Kind, const char*> order[2] = {
        {kde ? DialogProgram::Kind::KDialog : DialogProgram::Kind::Zenity,
         kde ? "kdialog" : "zenity"},
        {kde ? DialogProgram::Kind::Zenity : DialogProgram::Kind::KDialog,
         kde ? "zenity" : "kdialog"}};
    for (const auto& [kind, name] : order) {
        if (const std::optional<fs::path> p = on_path(search_path, name))
            return DialogProgram{kind, *p};
    }
    return std::nullopt;
}

std::vector<std::string> dialog_arguments(const DialogProgram& program,
                                          const FileDialogRequest& request) {
    std::vector<std::string> args;
    if (program.kind == DialogProgram::Kind::Zenity) {
        args = {"--file-selection", "--title=" + request.title, "--filename=" + start_at(request)};
        if (request.saving) args.emplace_back("--save");
        if (request.confirm_overwrite) args.emplace_back("--confirm-overwrite");
        for (const FileFilter& f : request.filters)
            args.push_back("--file-filter=" + f.label + " | " + patterns(f));
        return args;
    }
    // kdialog: the filters as one argument, one "Label (patterns)" a line.
    std::string filters;
    for (const FileFilter& f : request.filters)
        filters += (filters.empty() ? "" : "\n") + f.label + " (" + patterns(f) + ")";
    args = {"--title", request.title, request.saving ? "--getsavefilename" : "--getopenfilename",
            start_at(request), filters};
    return args;
}

NativeDialogResult run_dialog_program(const fs::path& program,
                                      const std::vector<std::string>& arguments,
                                      const std::atomic<bool>& stop) {
    const std::string name = program.filename().string();
    std::array<int, 2> out{-1, -1}, err{-1, -1};
    pid_t pid = -1;
    try {
        out = make_pipe();
        err = make_pipe();
    } catch (const std::exception& e) {
        for (int fd : {out[0], out[1]})
            if (fd >= 0) ::close(fd);
        return failed(e.what());
    }
    std::vector<std::string> argv_text{program.string()};
    argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& a : argv_text)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
    // A process group of its own, so that closing the dialog ends whatever it started too.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
    const int spawned =
        ::posix_spawn(&pid, program.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    ::close(err[1]);
    if (spawned != 0) {
        ::close(out[0]);
        ::close(err[0]);
        return failed("cannot run " + program.string() + ": " + std::strerror(spawned));
    }
    std::string printed, complaint;
    const bool stopped = read_until_closed({out[0], err[0]}, {&printed, &complaint}, stop);
    ::close(out[0]);
    ::close(err[0]);
    if (stopped) ::kill(-pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (stopped) return failed(name + " was closed");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 1) {
        NativeDialogResult r;
        r.outcome = NativeDialogResult::Outcome::Cancelled;
        return r;
    }
    const std::string said = last_line(complaint);
    if (!WIFEXITED(status)) {
        return failed(name + " ended by signal " + std::to_string(WTERMSIG(status)) +
                      (said.empty() ? "" : ": " + said));
    }
    if (WEXITSTATUS(status) != 0) {
        return failed(name + " exited with " + std::to_string(WEXITSTATUS(status)) +
                      (said.empty() ? "" : ": " + said));
    }
    // One path, on one line (a file name with a newline in it cannot come through zenity).
    while (!printed.empty() && (printed.back() == '\n' || printed.back() == '\r'))
        printed.pop_back();
    if (printed.empty()) return failed(name + " printed no file name");
    NativeDialogResult r;
    r.outcome = NativeDialogResult::Outcome::Chosen;
    r.path = printed;
    return r;
}

NativeFileDialog::~NativeFileDialog() {
    stop_ = true;
    join();
}

void NativeFileDialog::join() {
    if (thread_.joinable()) thread_.join();
}

void NativeFileDialog::start(const DialogProgram& program, const FileDialogRequest& request) {
    if (busy_) throw std::logic_error("a file dialog is open already");
    join();  // the last dialog's thread, whose answer was taken
    stop_ = false;
    busy_ = true;
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        result_.reset();
    }
    thread_ = std::thread([this, path = program.path, args = dialog_arguments(program, request)] {
        NativeDialogResult r = run_dialog_program(path, args, stop_);
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            result_ = std::move(r);
        }
        if (wake_ && !stop_) wake_();
    });
}

std::optional<NativeDialogResult> NativeFileDialog::take_result() {
    std::optional<NativeDialogResult> r;
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        r = std::move(result_);
        result_.reset();
    }
    if (r) {
        busy_ = false;
        join();
    }
    return r;
}

}  // namespace sandtin::editor
