#pragma once
// The sandtin sub-commands. Each takes the arguments after its name and returns the process
// exit code; user errors are thrown as UsageError or std::runtime_error and reported by main.

#include <string>
#include <vector>

namespace sandtin::cli {

int run_new(const std::vector<std::string>& args);
int run_info(const std::vector<std::string>& args);
int run_run(const std::vector<std::string>& args);
int run_bench(const std::vector<std::string>& args);
/// `sandtin bench erosion`: TIN vs grid run time against error (cmd_bench_erosion.cpp).
int run_bench_erosion(const std::vector<std::string>& args);
int run_bench_haptics(const std::vector<std::string>& args);
/// `sandtin bench gpu`: GPU relaxation, uploads, kernel times (cmd_bench_gpu.cpp).
int run_bench_gpu(const std::vector<std::string>& args);
int run_haptics(const std::vector<std::string>& args);
int run_demo(const std::vector<std::string>& args);
int run_import(const std::vector<std::string>& args);
int run_export(const std::vector<std::string>& args);
int run_stress(const std::vector<std::string>& args);

}  // namespace sandtin::cli
