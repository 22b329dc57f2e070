#pragma once
// Typed access to the fields of a JSON object with errors that name the field and its context,
// e.g. "operation 3 (stroke): field 'radius' must be a positive number". Unknown fields are
// errors too (reject_unknown), so a typo never silently falls back to a default.
// Header-only; users link nlohmann_json.

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "geom/vec2.hpp"

namespace sandtin {

/// An input error in a JSON document (script, tool or material file).
struct JsonInputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class JsonFields {
  public:
    JsonFields(const nlohmann::json& object, std::string context)
        : object_(object), context_(std::move(context)) {
        if (!object_.is_object()) fail("must be a JSON object");
    }

    const std::string& context() const { return context_; }
    [[noreturn]] void fail(const std::string& what) const {
        throw JsonInputError(context_ + ": " + what);
    }
    [[noreturn]] void fail_field(const std::string& key, const std::string& what) const {
        fail("field '" + key + "' " + what);
    }

    bool has(const std::string& key) const { return object_.contains(key); }
    const nlohmann::json* get(const std::string& key) {
        used_.insert(key);
        const auto it = object_.find(key);
        return it == object_.end() ? nullptr : &*it;
    }
    const nlohmann::json& required(const std::string& key) {
        const nlohmann::json* v = get(key);
        if (v == nullptr) fail("missing required field '" + key + "'");
        return *v;
    }

    double number(const std::string& key, double fallback) {
        const nlohmann::json* v = get(key);
        return v == nullptr ? fallback : as_number(key, *v);
    }
    double required_number(const std::string& key) { return as_number(key, required(key)); }
    double positive(const std::string& key, double fallback) {
        const double v = number(key, fallback);
        if (!(v > 0.0)) fail_field(key, "must be a positive number");
        return v;
    }
    double non_negative(const std::string& key, double fallback) {
        const double v = number(key, fallback);
        if (!(v >= 0.0)) fail_field(key, "must be zero or positive");
        return v;
    }
    double in_range(const std::string& key, double fallback, double lo, double hi) {
        const double v = number(key, fallback);
        if (!(v >= lo && v <= hi)) {
            fail_field(key, "must lie in [" + format(lo) + ", " + format(hi) + "]");
        }
        return v;
    }
    std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t lo,
                         std::int64_t hi) {
        const nlohmann::json* v = get(key);
        if (v == nullptr) return fallback;
        if (!v->is_number_integer() && !v->is_number_unsigned())
            fail_field(key, "must be an integer");
        const auto i = v->get<std::int64_t>();
        if (i < lo || i > hi) {
            fail_field(key, "must lie in " + std::to_string(lo) + ".." + std::to_string(hi));
        }
        return i;
    }
    bool boolean(const std::string& key, bool fallback) {
        const nlohmann::json* v = get(key);
        if (v == nullptr) return fallback;
        if (!v->is_boolean()) fail_field(key, "must be true or false");
        return v->get<bool>();
    }
    std::string text(const std::string& key, const std::string& fallback) {
        const nlohmann::json* v = get(key);
        if (v == nullptr) return fallback;
        if (!v->is_string()) fail_field(key, "must be a string");
        return v->get<std::string>();
    }
    std::string choice(const std::string& key, const std::string& fallback,
                       std::initializer_list<const char*> allowed) {
        return choice(key, fallback, std::span<const char* const>(allowed.begin(), allowed.size()));
    }
    std::string choice(const std::string& key, const std::string& fallback,
                       std::span<const char* const> allowed) {
        const std::string v = text(key, fallback);
        std::string list;
        for (const char* a : allowed) {
            if (v == a) return v;
            list += list.empty() ? "" : ", ";
            list += a;
        }
        fail_field(key, "is '" + v + "'; expected one of: " + list);
    }
    Vec2 point(const std::string& key) { return as_point(key, required(key)); }
    /// A disc given as 'centre' ([x, y]) and 'radius' (> 0): both, or neither (nothing).
    /// `purpose` finishes the error "give both 'centre' and 'radius' <purpose>, or neither".
    struct Disc {
        Vec2 centre;
        double radius = 0.0;
    };
    std::optional<Disc> disc(const std::string& purpose) {
        if (has("centre") != has("radius"))
            fail("give both 'centre' and 'radius' " + purpose + ", or neither");
        if (!has("centre")) return std::nullopt;
        return Disc{point("centre"), positive("radius", 0.0)};
    }
    std::vector<Vec2> points(const std::string& key, std::size_t min_count) {
        const nlohmann::json& v = required(key);
        if (!v.is_array()) fail_field(key, "must be an array of [x, y] points");
        std::vector<Vec2> out;
        for (const nlohmann::json& p : v)
            out.push_back(as_point(key, p));
        if (out.size() < min_count) {
            fail_field(key, "needs at least " + std::to_string(min_count) + " points");
        }
        return out;
    }

    /// Throws for any field that no accessor asked for.
    void reject_unknown() const {
        for (auto it = object_.begin(); it != object_.end(); ++it) {
            if (used_.count(it.key()) == 0) fail("unknown field '" + it.key() + "'");
        }
    }

  private:
    static std::string format(double v) {
        std::ostringstream out;  // 0.02, 1, 1e+09: as written, without padding zeros
        out << v;
        return out.str();
    }
    double as_number(const std::string& key, const nlohmann::json& v) const {
        if (!v.is_number()) fail_field(key, "must be a number");
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail_field(key, "must be finite");
        return d;
    }
    Vec2 as_point(const std::string& key, const nlohmann::json& v) const {
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
            fail_field(key, "must hold [x, y] points (two numbers)");
        }
        const Vec2 p{v[0].get<double>(), v[1].get<double>()};
        if (!is_finite(p)) fail_field(key, "has a non-finite coordinate");
        return p;
    }

    const nlohmann::json& object_;
    std::string context_;
    std::set<std::string> used_;
};

}  // namespace sandtin
