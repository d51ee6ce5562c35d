// A file's bytes collected and handed on in pieces of about a megabyte: text and numbers for
// the text formats, raw little-endian values for the binary ones.
#pragma once

#include <charconv>
#include <cstddef>
#include <functional>
#include <string>

namespace ddt {

// Where a file's bytes go, in pieces of any size.
using ByteSink = std::function<void(const char* data, size_t size)>;

// Collects a file's bytes and hands them to the sink in pieces of about a megabyte.
class ByteBuffer {
public:
    explicit ByteBuffer(const ByteSink& sink) : sink_(sink) { bytes_.reserve(kPiece + 256); }

    void text(const std::string& s) { append(s.data(), s.size()); }
    template <typename T>
    void binary(T value) {  // little-endian, as x86 and ARM store it
        append(reinterpret_cast<const char*>(&value), sizeof(value));
    }
    template <typename T>
    void number(T value) {  // the shortest text that reads back as the same value
        char digits[32];
        const auto [end, error] = std::to_chars(digits, digits + sizeof(digits), value);
        append(digits, size_t(end - digits));
    }
    void flush() {
        if (!bytes_.empty()) sink_(bytes_.data(), bytes_.size());
        bytes_.clear();
    }

private:
    static constexpr size_t kPiece = size_t(1) << 20;
    void append(const char* data, size_t size) {
        bytes_.append(data, size);
        if (bytes_.size() >= kPiece) flush();
    }

    const ByteSink& sink_;
    std::string bytes_;
};

}  // namespace ddt
