#include "io/script_lines.hpp"

#include <string>

#include <nlohmann/json.hpp>

#include "util/json_document.hpp"

namespace sandtin {

namespace {

/// Records the line on which each operation object starts.
class OperationLines : public nlohmann::json_sax<nlohmann::json> {
  public:
    /// What the iterators feeding this pass advance.
    LineCountingIterator::Cursor* cursor() { return &cursor_; }
    std::vector<std::size_t> lines;

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return number(); }
    bool number_unsigned(number_unsigned_t) override { return number(); }
    bool number_float(number_float_t, const string_t&) override { return number(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        record();
        stack_.push_back({false, pending_key_});
        pending_key_.clear();
        return true;
    }
    bool key(string_t& k) override {
        pending_key_ = k;
        return true;
    }
    bool end_object() override {
        stack_.pop_back();
        return true;
    }
    bool start_array(std::size_t) override {
        record();
        stack_.push_back({true, pending_key_});
        pending_key_.clear();
        return true;
    }
    bool end_array() override {
        stack_.pop_back();
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;  // parse_json_document has reported it
    }

  private:
    struct Level {
        bool array;
        std::string key;
    };
    bool value() {
        record();
        pending_key_.clear();
        return true;
    }
    bool number() {
        if (in_operations()) lines.push_back(cursor_.line_before_lookahead());
        pending_key_.clear();
        return true;
    }
    /// Any element of the operations array, object or not, starts on the current line.
    void record() {
        if (in_operations()) lines.push_back(cursor_.newlines + 1);
    }
    bool in_operations() const {
        // A bare top-level array, or the array under the top-level key "operations".
        if (stack_.size() == 1) return stack_[0].array;
        return stack_.size() == 2 && !stack_[0].array && stack_[1].array &&
               stack_[1].key == "operations";
    }
    LineCountingIterator::Cursor cursor_;
    std::vector<Level> stack_;
    std::string pending_key_;
};

}  // namespace

std::vector<std::size_t> operation_start_lines(std::string_view text) {
    OperationLines lines;
    nlohmann::json::sax_parse(LineCountingIterator(text.data(), lines.cursor()),
                              LineCountingIterator(text.data() + text.size(), lines.cursor()),
                              &lines);
    return lines.lines;
}

}  // namespace sandtin
