#pragma once
// Plain bytes for results that cross processes (work_farm.hpp): trivially copyable values and strings appended in
// order and read back in the same order, bit for bit (doubles keep every bit, so the output does not depend on
// which process computed a cell). Both ends are the same binary, so no byte-order conversion.
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace lienewton {

class ByteWriter {
 public:
  template <class T>
    requires std::is_trivially_copyable_v<T>
  ByteWriter& put(const T& value) {
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
    return *this;
  }
  ByteWriter& put_doubles(const double* values, std::size_t count) {
    bytes_.append(reinterpret_cast<const char*>(values), count * sizeof(double));
    return *this;
  }
  ByteWriter& put_string(const std::string& text) {
    put(text.size());
    bytes_ += text;
    return *this;
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
    requires std::is_trivially_copyable_v<T>
  T get() {
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  void get_doubles(double* values, std::size_t count) {
    std::memcpy(values, take(count * sizeof(double)), count * sizeof(double));
  }
  std::string get_string() {
    const auto size = get<std::size_t>();
    return std::string(take(size), size);
  }

 private:
  const char* take(std::size_t size) {
    if (size > bytes_.size() - position_) throw std::runtime_error("ByteReader: truncated message");
    const char* at = bytes_.data() + position_;
    position_ += size;
    return at;
  }
  const std::string& bytes_;
  std::size_t position_ = 0;
};

}  // namespace lienewton
