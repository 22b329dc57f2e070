#pragma once
// Whole JSON documents read from users' files (scripts, tools, materials, recordings), with
// errors that name the file and the line. Three things nlohmann accepts or reports without a
// line are errors here, each with its line:
//  - a syntax error (nlohmann gives a byte offset);
//  - a number beyond double's range such as 1e400 (nlohmann throws out_of_range, no offset);
//  - an object that gives a key twice (nlohmann keeps the last value, so one would be ignored).

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <iterator>
#include <string>
#include <string_view>

namespace sandtin {

/// Parses `text`. Throws JsonInputError "<name>:<line>: ..." (util/json_fields.hpp).
nlohmann::json parse_json_document(std::string_view text, const std::string& name);

/// Reads `path` and parses it; errors name the path. `what` says what the file is for the
/// message when it cannot be opened, e.g. "tool file".
nlohmann::json read_json_document(const std::filesystem::path& path, const std::string& what);

/// An input iterator over characters that counts the newlines it has passed, for SAX passes
/// that need to say on which line an event happened.
class LineCountingIterator {
  public:
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    struct Cursor {
        std::size_t newlines = 0;
        char last = 0;  ///< the character consumed last
        /// The line of a token the lexer has just finished: it knows a number ended only by
        /// reading one character past it, which may have been the newline.
        std::size_t line_before_lookahead() const { return newlines - (last == '\n' ? 1 : 0) + 1; }
    };

    LineCountingIterator() = default;
    LineCountingIterator(const char* p, Cursor* cursor) : p_(p), cursor_(cursor) {}
    reference operator*() const { return *p_; }
    LineCountingIterator& operator++() {
        if (*p_ == '\n') ++cursor_->newlines;
        cursor_->last = *p_;
        ++p_;
        return *this;
    }
    LineCountingIterator operator++(int) {
        LineCountingIterator old = *this;
        ++*this;
        return old;
    }
    friend bool operator==(const LineCountingIterator& a, const LineCountingIterator& b) {
        return a.p_ == b.p_;
    }

  private:
    const char* p_ = nullptr;
    Cursor* cursor_ = nullptr;
};

}  // namespace sandtin
