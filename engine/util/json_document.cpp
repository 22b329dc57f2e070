#include "util/json_document.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <vector>

#include "util/atomic_file.hpp"
#include "util/json_fields.hpp"

namespace sandtin {

namespace {

/// One pass over a document that nlohmann parsed or refused: the first key an object gives
/// twice, and the line where parsing stopped.
class KeysAndStop : public nlohmann::json_sax<nlohmann::json> {
  public:
    explicit KeysAndStop(const LineCountingIterator::Cursor* cursor) : cursor_(cursor) {}

    std::optional<std::pair<std::string, std::size_t>> duplicate;  ///< key, line
    std::optional<std::size_t> stop_line;

    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override {
        objects_.emplace_back();
        return true;
    }
    bool key(string_t& k) override {
        if (!objects_.back().insert(k).second && !duplicate)
            duplicate.emplace(k, cursor_->newlines + 1);
        return true;
    }
    bool end_object() override {
        objects_.pop_back();
        return true;
    }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        stop_line = cursor_->line_before_lookahead();
        return false;
    }

  private:
    const LineCountingIterator::Cursor* cursor_;
    std::vector<std::set<std::string>> objects_;  ///< the keys of each open object so far
};

KeysAndStop scan(std::string_view text, LineCountingIterator::Cursor& cursor) {
    KeysAndStop scanner(&cursor);
    nlohmann::json::sax_parse(LineCountingIterator(text.data(), &cursor),
                              LineCountingIterator(text.data() + text.size(), &cursor), &scanner);
    return scanner;
}

}  // namespace

nlohmann::json parse_json_document(std::string_view text, const std::string& name) {
    nlohmann::json document;
    try {
        document = nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error& e) {
        const std::size_t offset = std::min<std::size_t>(e.byte, text.size());
        const std::size_t line =
            1 + static_cast<std::size_t>(std::count(
                    text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
        throw JsonInputError(name + ":" + std::to_string(line) + ": not valid JSON: " + e.what());
    } catch (const nlohmann::json::exception& e) {
        // Valid syntax the parser cannot hold: the SAX pass stops at the same token.
        LineCountingIterator::Cursor cursor;
        const KeysAndStop s = scan(text, cursor);
        const std::string line = s.stop_line ? ":" + std::to_string(*s.stop_line) : std::string();
        throw JsonInputError(name + line + ": not valid JSON: " + e.what());
    }
    LineCountingIterator::Cursor cursor;
    const KeysAndStop s = scan(text, cursor);
    if (s.duplicate) {
        throw JsonInputError(name + ":" + std::to_string(s.duplicate->second) + ": the key '" +
                             s.duplicate->first +
                             "' is given twice in one object; only one value can count");
    }
    return document;
}

nlohmann::json read_json_document(const std::filesystem::path& path, const std::string& what) {
    std::vector<std::uint8_t> bytes;
    try {
        bytes = read_file(path, 1ull << 28);
    } catch (const std::exception& e) {
        throw JsonInputError(what + ": " + e.what());  // read_file names the path
    }
    return parse_json_document(
        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string());
}

}  // namespace sandtin
