// sandtin: the command-line front end (new, info, run, export, bench, stress, demo).

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/session_file.hpp"

namespace {

constexpr const char* kHelp = R"(sandtin - interactive sand terrain on a TIN

usage: sandtin <command> [options]

commands:
  new     create a terrain:   sandtin new (--flat W H [--points N] [--seed S] | --grid W H NX NY)
                              [--height Z] -o scene.sandtin
  info    describe a session: sandtin info scene.sandtin [--json]
  run     apply a script:     sandtin run script.json [-i in.sandtin] -o out.sandtin [--physics cpu|gpu] [--json]
  import  heightmap to TIN:   sandtin import FILE --max-error E [--max-points N] -o scene.sandtin
  export  mesh or map:        sandtin export scene.sandtin -o out.(obj|ply|stl|gltf|glb|png|exr)
  bench   benchmarks (JSON):  sandtin bench (tin | groove | import | history | erosion | gpu | haptics)
                              [--quick] [--json]; every benchmark and its options: README.md
  haptics live editing with a haptic device driven over UDP by a driver process:
                              sandtin haptics serve -o out.sandtin [--port P] [--record R]
  stress  random operations, invariants checked after each:
                              sandtin stress [--seed S] [--ops N] [--json]
  demo    the default batch job: sculpt the default scene, save the result, say how to open it:
                              sandtin demo [-o out.sandtin] [--json]

sandtin <command> --help prints the command's usage, sandtin --version the version; README.md has every option, its default
and its unit. Errors go to stderr and the exit code is non-zero. On a terminal, import, export, run,
stress and bench draw their progress on stderr.
)";

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        std::cerr << kHelp;
        return 2;
    }
    const std::string command = args.front();
    args.erase(args.begin());
    try {
        if (command == "new") return sandtin::cli::run_new(args);
        if (command == "info") return sandtin::cli::run_info(args);
        if (command == "run") return sandtin::cli::run_run(args);
        if (command == "bench") return sandtin::cli::run_bench(args);
        if (command == "demo") return sandtin::cli::run_demo(args);
        if (command == "import") return sandtin::cli::run_import(args);
        if (command == "export") return sandtin::cli::run_export(args);
        if (command == "haptics") return sandtin::cli::run_haptics(args);
        if (command == "stress") return sandtin::cli::run_stress(args);
        if (command == "--version" || command == "version") {
            std::cout << "sandtin " << SANDTIN_VERSION << " (session format "
                      << sandtin::kSessionFormatVersion << ", reads "
                      << sandtin::kOldestSessionFormatVersion << " to "
                      << sandtin::kSessionFormatVersion << ")\n";
            return 0;
        }
        if (command == "help" || command == "--help" || command == "-h") {
            std::cout << kHelp;
            return 0;
        }
        std::cerr << "sandtin: error: unknown command '" << command << "'\n\n" << kHelp;
        return 2;
    } catch (const sandtin::cli::HelpRequested& e) {
        std::cout << "usage: " << e.what()
                  << "\nEvery option, its default and its unit: README.md\n";
        return 0;
    } catch (const sandtin::cli::UsageError& e) {
        std::cerr << "sandtin " << command << ": error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "sandtin " << command << ": error: " << e.what() << "\n";
        return 1;
    }
}
