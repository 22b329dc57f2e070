#include "arguments.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace sandtin::cli {

Arguments::Arguments(const std::vector<std::string>& args, const std::map<std::string, int>& spec) {
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--help" || a == "-h") {
            help_ = true;
            continue;
        }
        if (a.size() > 1 && a[0] == '-' &&
            !(a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.'))) {
            const auto it = spec.find(a);
            if (it == spec.end()) throw UsageError("unknown option '" + a + "'");
            if (values_.count(a) > 0) throw UsageError("option '" + a + "' is given twice");
            std::vector<std::string> vals;
            for (int k = 0; k < it->second; ++k) {
                if (i + 1 >= args.size()) {
                    throw UsageError("option '" + a + "' needs " + std::to_string(it->second) +
                                     " value(s)");
                }
                vals.push_back(args[++i]);
            }
            values_[a] = std::move(vals);
        } else {
            positionals_.push_back(a);
        }
    }
}

const std::vector<std::string>& Arguments::values(const std::string& option) const {
    const auto it = values_.find(option);
    if (it == values_.end()) throw UsageError("missing required option '" + option + "'");
    return it->second;
}

double Arguments::number(const std::string& option, std::size_t index) const {
    return parse_number(values(option).at(index), "option '" + option + "'");
}

std::uint64_t Arguments::count(const std::string& option, std::size_t index) const {
    return parse_count(values(option).at(index), "option '" + option + "'");
}

void Arguments::require_positionals(std::size_t n, const std::string& usage) const {
    if (help_) throw HelpRequested(usage);
    if (positionals_.size() == n) return;
    if (positionals_.size() > n) {
        throw UsageError("unexpected argument '" + positionals_[n] + "'\nusage: " + usage);
    }
    throw UsageError("missing " + std::to_string(n - positionals_.size()) + " of its " +
                     std::to_string(n) + " argument(s)\nusage: " + usage);
}

double parse_number(const std::string& text, const std::string& what) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
        throw UsageError(what + ": '" + text + "' is not a finite number");
    }
    return v;
}

std::uint64_t parse_count(const std::string& text, const std::string& what) {
    char* end = nullptr;
    // strtoull skips leading spaces and accepts a sign, wrapping " -1" to 2^64 - 1: only
    // digits are a count.
    if (text.empty() || std::isdigit(static_cast<unsigned char>(text[0])) == 0)
        throw UsageError(what + ": '" + text + "' is not a non-negative integer");
    errno = 0;
    const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || errno == ERANGE) {
        throw UsageError(what + ": '" + text + "' is not a non-negative integer");
    }
    return v;
}

}  // namespace sandtin::cli
