// sandtin stress: random operations with invariant checks after each; on the first failure,
// a minimal reproducing script.

#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress_line.hpp"
#include "stress/stress_runner.hpp"

namespace sandtin::cli {

namespace {
constexpr const char* kStressUsage =
    "sandtin stress [--seed S] [--ops N] [--points P] [--check-every K] [--work-dir DIR] "
    "[--no-minimise] [--repro FILE] [--json]";
}

int run_stress(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--seed", 1},
                               {"--ops", 1},
                               {"--points", 1},
                               {"--check-every", 1},
                               {"--work-dir", 1},
                               {"--no-minimise", 0},
                               {"--repro", 1},
                               {"--json", 0}});
    args.require_positionals(0, kStressUsage);
    StressOptions options;
    options.seed = args.count_or("--seed", 1);
    options.operations = args.count_or("--ops", 1000);
    options.terrain_points = args.count_or("--points", 3000);
    if (options.terrain_points > 10'000'000) throw UsageError("--points must be at most 10000000");
    // The triangulation's full validity check after every Kth operation (and every save and
    // the last one); the other invariants after every operation.
    options.full_check_every = args.count_or("--check-every", 1);
    if (options.full_check_every == 0) throw UsageError("--check-every must be at least 1");
    options.work_dir = args.text_or("--work-dir", "");
    options.minimise = !args.has("--no-minimise");
    const bool json = args.has("--json");
    ProgressLine progress("stress seed " + std::to_string(options.seed));
    std::function<void(std::size_t)> after_operation;
    if (const ProgressCallback draw = progress.callback()) {
        after_operation = [draw, &options](std::size_t done) {
            const std::string stage =
                "operation " + std::to_string(done) + " of " + std::to_string(options.operations);
            draw({static_cast<double>(done) / static_cast<double>(options.operations), stage});
        };
    }
    const StressReport report = run_stress(options, after_operation);
    // A failure stops the session early: the line ends where it stopped, not at 100 %.
    if (report.failure) {
        progress.stop();
    } else {
        progress.finish();
    }
    if (report.failure && args.has("--repro")) {
        std::ofstream(args.text("--repro")) << report.failure->script.dump(2) << "\n";
    }
    if (json) {
        std::cout << report.to_json().dump(2) << "\n";
    } else if (report.failure) {
        const StressFailure& f = *report.failure;
        std::cout << "stress seed " << report.seed << ": FAILED at operation " << f.operation
                  << " (" << f.invariant << "): " << f.detail << "\n"
                  << "reproducing script (" << f.script_operations
                  << " operations; replay with `sandtin run script.json -o out.sandtin`):\n"
                  << f.script.dump(2) << "\n";
    } else {
        std::cout << "stress seed " << report.seed << ": " << report.operations_run
                  << " operations, all invariants held (" << report.rejected
                  << " degenerate operations rejected cleanly); max " << report.max_vertices
                  << " vertices, " << report.max_constraints
                  << " constraints; max relative volume residual " << report.max_volume_residual
                  << "; " << report.seconds << " s\n";
    }
    return report.failure ? 1 : 0;
}

}  // namespace sandtin::cli
