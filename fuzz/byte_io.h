#pragma once
// Structured fuzz inputs: fixed-size little-endian values read front to back, and the writer the
// corpus generator uses to make seeds of the same layout.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace stocs::fuzz {

/// Reads values front to back; past the end every value is zero.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  template <class T>
  T take() {
    T v{};
    if (size_ - pos_ >= sizeof(T)) {
      std::memcpy(&v, data_ + pos_, sizeof(T));
      pos_ += sizeof(T);
    } else {
      pos_ = size_;
    }
    return v;
  }
  template <size_t N>
  const char* pick(const char* const (&names)[N]) {
    return names[take<uint8_t>() % N];
  }
  std::vector<uint8_t> rest() { return {data_ + pos_, data_ + size_}; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

/// The generator's side of ByteReader.
class ByteWriter {
 public:
  template <class T>
  ByteWriter& put(T v) {
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes_.append(p, sizeof(T));
    return *this;
  }
  ByteWriter& append(const std::string& raw) {
    bytes_ += raw;
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

}  // namespace stocs::fuzz
