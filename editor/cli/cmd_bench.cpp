// sandtin bench: measurements printed as JSON (see tests/bench/).

#include <iostream>

#include "arguments.hpp"
#include "bench_groove.hpp"
#include "bench_history.hpp"
#include "bench_import.hpp"
#include "bench_tin.hpp"
#include "bench_water.hpp"
#include "commands.hpp"
#include "progress_line.hpp"

namespace sandtin::cli {

int run_bench(const std::vector<std::string>& raw) {
    if (!raw.empty() && raw[0] == "erosion") return run_bench_erosion(raw);
    // The haptic loop benchmark has its own options (cmd_bench_haptics.cpp).
    if (!raw.empty() && raw.front() == "haptics")
        return run_bench_haptics(std::vector<std::string>(raw.begin() + 1, raw.end()));
    if (!raw.empty() && raw.front() == "gpu")
        return run_bench_gpu(std::vector<std::string>(raw.begin() + 1, raw.end()));
    const Arguments args(raw, {{"--quick", 0}, {"--json", 0}, {"--tool", 1}});
    args.require_positionals(
        1,
        "sandtin bench (tin | groove [--tool NAME] | import | history | water | erosion | gpu | "
        "haptics) "
        "[--quick] [--json]");
    bench::BenchConfig config;
    config.quick = args.has("--quick");
    const std::string which = args.positionals()[0];
    if (args.has("--tool")) {
        if (which != "groove") throw UsageError("--tool applies to 'bench groove' only");
        config.tool = args.text("--tool");
    }
    if (which != "tin" && which != "groove" && which != "import" && which != "history" &&
        which != "water") {
        throw UsageError("unknown benchmark '" + which +
                         "' (available: tin, groove, import, history, water, erosion, gpu, "
                         "haptics)");
    }
    ProgressLine progress("bench " + which);
    config.progress = progress.callback();
    nlohmann::json result;
    if (which == "tin") {
        result = bench::bench_tin(config);
    } else if (which == "groove") {
        result = bench::bench_groove(config);
    } else if (which == "import") {
        result = bench::bench_import(config);
    } else if (which == "water") {
        result = bench::bench_water(config);
    } else {
        result = bench::bench_history(config, config.progress);
    }
    progress.finish();
    std::cout << result.dump(2) << "\n";
    return 0;
}

}  // namespace sandtin::cli
