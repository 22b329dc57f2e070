#pragma once
// Command-line arguments: positionals plus --options with a fixed number of values. Anything
// unexpected is an error that names the argument, never a silent default.

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sandtin::cli {

/// A user error on the command line or in an input file: printed without a stack of context.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// --help or -h on a command: main prints `what()`, the command's usage, on stdout and exits 0.
struct HelpRequested : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Arguments {
  public:
    /// `spec` maps each allowed option (with its dashes) to the number of values it takes.
    Arguments(const std::vector<std::string>& args, const std::map<std::string, int>& spec);

    const std::vector<std::string>& positionals() const { return positionals_; }
    bool has(const std::string& option) const { return values_.count(option) > 0; }
    /// The values of an option; throws UsageError when it is missing.
    const std::vector<std::string>& values(const std::string& option) const;

    std::string text(const std::string& option) const { return values(option).at(0); }
    std::string text_or(const std::string& option, const std::string& fallback) const {
        return has(option) ? text(option) : fallback;
    }
    double number(const std::string& option, std::size_t index = 0) const;
    double number_or(const std::string& option, double fallback) const {
        return has(option) ? number(option) : fallback;
    }
    std::uint64_t count(const std::string& option, std::size_t index = 0) const;
    std::uint64_t count_or(const std::string& option, std::uint64_t fallback) const {
        return has(option) ? count(option) : fallback;
    }
    /// Throws HelpRequested with `usage` when --help or -h was given (every command calls this
    /// first), else UsageError naming what is missing or extra unless there are exactly `n`
    /// positional arguments.
    void require_positionals(std::size_t n, const std::string& usage) const;

  private:
    bool help_ = false;
    std::vector<std::string> positionals_;
    std::map<std::string, std::vector<std::string>> values_;
};

/// Parses a finite number; throws UsageError naming `what` otherwise.
double parse_number(const std::string& text, const std::string& what);
/// Parses a non-negative integer; throws UsageError naming `what` otherwise.
std::uint64_t parse_count(const std::string& text, const std::string& what);

}  // namespace sandtin::cli
