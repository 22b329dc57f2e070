// sandtin-editor [scene.sandtin] [--script s.json] [--frames N] [--screenshot out.png]
//                [--size WxH] [--stats out.json] [--save-after out.sandtin]
//                [--idle-seconds S] [--settings path] [--widget-map out.json] [--validation]
//
// A separate executable rather than a `sandtin editor` subcommand: the CLI stays free of
// GLFW, Vulkan surfaces and ImGui, so it runs and links on headless machines without them.

#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "editor_app.hpp"
#include "heap_reuse.hpp"
#include "io/session_name.hpp"

namespace {

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr,
                 "sandtin-editor: %s\nusage: sandtin-editor [scene.sandtin] [--script s.json] "
                 "[--frames N] [--screenshot out.png] [--size WxH] [--stats out.json] "
                 "[--save-after out.sandtin] [--idle-seconds S] [--settings path] "
                 "[--widget-map out.json] [--validation]\n",
                 problem.c_str());
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    sandtin::editor::keep_freed_heap_for_reuse();
    sandtin::editor::EditorOptions o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            // "--stats --settings s.json" would otherwise write the stats to "--settings" and
            // open s.json as the scene.
            if (i + 1 >= argc || std::string(argv[i + 1]).starts_with("--"))
                usage("option " + a + " needs a value");
            return argv[++i];
        };
        try {
            if (a == "--script")
                o.script = value();
            else if (a == "--screenshot")
                o.screenshot = value();
            else if (a == "--stats")
                o.stats = value();
            else if (a == "--settings")
                o.settings = value();
            else if (a == "--widget-map")
                o.widget_map = value();
            else if (a == "--save-after")
                o.save_after = value();
            else if (a == "--frames")
                o.frames = std::stoi(value());
            else if (a == "--idle-seconds")
                o.idle_seconds = std::stod(value());
            else if (a == "--validation")
                o.validation = true;
            else if (a == "--size") {
                const std::string s = value();
                const auto x = s.find('x');
                if (x == std::string::npos) usage("--size wants WxH, got '" + s + "'");
                o.width = std::stoi(s.substr(0, x));
                o.height = std::stoi(s.substr(x + 1));
            } else if (!a.empty() && a[0] == '-')
                usage("unknown option " + a);
            else if (o.scene.empty())
                o.scene = a;
            else
                usage("more than one scene given");
        } catch (const std::logic_error&) {
            usage("bad number for " + a);
        }
    }
    if (o.frames < 0 || o.width < 64 || o.height < 64 || o.width > 8192 || o.height > 8192)
        usage("frames must be >= 0 and the size between 64 and 8192 pixels");
    // Before the work, not after it, as `sandtin` checks its -o.
    if (const std::optional<std::string> problem = sandtin::session_name_problem(o.save_after);
        !o.save_after.empty() && problem) {
        usage("--save-after '" + o.save_after.string() + "': " + *problem +
              " (sandtin export writes meshes and maps)");
    }
    try {
        return sandtin::editor::run_editor(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sandtin-editor: %s\n", e.what());
        return 1;
    }
}
