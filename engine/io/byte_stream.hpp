#pragma once
// Little-endian binary encoding with bounds checks. The reader never trusts a count from the
// file: it checks that the bytes exist before it allocates, so a crafted or truncated file
// fails with a message instead of exhausting memory or reading past the end.

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "util/prepare_for_writing.hpp"

namespace sandtin {

static_assert(std::endian::native == std::endian::little, "sandtin files are little-endian");

class ByteWriter {
  public:
    template <class T>
    requires std::is_trivially_copyable_v<T>
    void put(const T& value) {
        const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
        bytes_.insert(bytes_.end(), p, p + sizeof(T));
    }
    template <class T>
    requires std::is_trivially_copyable_v<T>
    void put_array(std::span<const T> values) {
        put<std::uint64_t>(values.size());
        const auto* p = reinterpret_cast<const std::uint8_t*>(values.data());
        bytes_.insert(bytes_.end(), p, p + values.size_bytes());
    }
    void put_bytes(std::span<const std::uint8_t> data) {
        bytes_.insert(bytes_.end(), data.begin(), data.end());
    }
    void put_string(const std::string& s) {
        put<std::uint64_t>(s.size());
        bytes_.insert(bytes_.end(), s.begin(), s.end());
    }
    /// Overwrites sizeof(T) bytes written earlier at `offset` (a length or checksum known only
    /// once what follows it is written).
    template <class T>
    requires std::is_trivially_copyable_v<T>
    void put_at(std::size_t offset, const T& value) {
        if (offset + sizeof(T) > bytes_.size())
            throw std::logic_error("ByteWriter::put_at past the bytes written");
        std::memcpy(bytes_.data() + offset, &value, sizeof(T));
    }
    /// Room for `bytes` more, prepared for writing: one allocation for a whole file.
    void reserve(std::size_t bytes) { reserve_for_writing(bytes_, bytes_.size() + bytes); }
    std::size_t size() const { return bytes_.size(); }
    std::vector<std::uint8_t>& bytes() { return bytes_; }

  private:
    std::vector<std::uint8_t> bytes_;
};

class ByteReader {
  public:
    ByteReader(std::span<const std::uint8_t> data, std::string context)
        : data_(data), context_(std::move(context)) {}

    template <class T>
    requires std::is_trivially_copyable_v<T> T get() {
        need(sizeof(T), "a value");
        T value;
        std::memcpy(&value, data_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return value;
    }
    template <class T>
    requires std::is_trivially_copyable_v<T> std::vector<T> get_array(
        std::uint64_t max_count = UINT32_MAX) {
        const auto count = get<std::uint64_t>();
        if (count > max_count) fail("an array of " + std::to_string(count) + " items is too long");
        need(count * sizeof(T), "an array of " + std::to_string(count) + " items");
        std::vector<T> values;
        reserve_for_writing(values, count);  // a terrain's arrays run to tens of MB
        values.resize(count);
        if (count > 0) std::memcpy(values.data(), data_.data() + pos_, count * sizeof(T));
        pos_ += count * sizeof(T);
        return values;
    }
    std::string get_string(std::uint64_t max_length = 1u << 30) {
        const auto n = get<std::uint64_t>();
        if (n > max_length) fail("a string of " + std::to_string(n) + " bytes is too long");
        need(n, "a string");
        std::string s(reinterpret_cast<const char*>(data_.data() + pos_), n);
        pos_ += n;
        return s;
    }
    std::span<const std::uint8_t> get_bytes(std::uint64_t n) {
        need(n, "a block");
        auto out = data_.subspan(pos_, n);
        pos_ += n;
        return out;
    }
    std::size_t remaining() const { return data_.size() - pos_; }
    bool at_end() const { return pos_ == data_.size(); }
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(context_ + ": " + what + " (at byte " + std::to_string(pos_) +
                                 ")");
    }

  private:
    void need(std::uint64_t n, const std::string& what) const {
        if (n > remaining()) fail("file is truncated: expected " + what);
    }

    std::span<const std::uint8_t> data_;
    std::size_t pos_ = 0;
    std::string context_;
};

}  // namespace sandtin
