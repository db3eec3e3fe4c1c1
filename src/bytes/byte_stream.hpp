#pragma once
// Little-endian bytes in and out (docs/map-format.md): a writer that appends values to a string,
// and a reader that takes them in order and names the byte offset of whatever it refuses.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace eco::detail {

// Values are copied as they lie in memory: the format is little-endian, as this machine is.
static_assert(std::endian::native == std::endian::little, "map files are written on little-endian machines");

class ByteWriter {
 public:
  template <class T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    out_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void put_bytes(std::string_view bytes) { out_.append(bytes); }
  [[nodiscard]] std::string& bytes() { return out_; }

 private:
  std::string out_;
};

/// Thrown for a file whose bytes do not make a map: what and where.
struct ByteError : std::runtime_error {
  ByteError(std::size_t at, const std::string& what) : std::runtime_error(what), offset(at) {}
  std::size_t offset;
};

class ByteReader {
 public:
  /// Reads `bytes` from offset `start`.
  explicit ByteReader(std::string_view bytes, std::size_t start = 0) : bytes_(bytes), at_(start) {}

  template <class T>
  T get(const char* what) {
    static_assert(std::is_arithmetic_v<T>);
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  /// `n` values into `out`.
  template <class T>
  void get_values(std::vector<T>& out, std::size_t n, const char* what) {
    static_assert(std::is_arithmetic_v<T>);
    if (n > left() / sizeof(T)) fail(std::string(what) + ": the file ends inside its " + std::to_string(n) + " values");
    out.resize(n);
    if (n > 0) std::memcpy(out.data(), bytes_.data() + at_, n * sizeof(T));  // data() may be null when empty
    at_ += n * sizeof(T);
  }
  /// The next `n` values of type T where they lie in the bytes read (at any alignment: read them
  /// with memcpy), and moves past them.
  template <class T>
  const std::byte* get_in_place(std::size_t n, const char* what) {
    static_assert(std::is_arithmetic_v<T>);
    if (n > left() / sizeof(T)) fail(std::string(what) + ": the file ends inside its " + std::to_string(n) + " values");
    const auto* at = reinterpret_cast<const std::byte*>(bytes_.data() + at_);
    at_ += n * sizeof(T);
    return at;
  }
  /// A count, then as many values.
  template <class T>
  std::vector<T> get_array(const char* what) {
    std::vector<T> values;
    get_values(values, get<std::uint64_t>(what), what);
    return values;
  }
  /// Throws a ByteError at `at` (default: the next byte).
  [[noreturn]] void fail(const std::string& what) const { throw ByteError(at_, what); }
  [[noreturn]] static void fail_at(std::size_t at, const std::string& what) { throw ByteError(at, what); }
  [[nodiscard]] std::size_t offset() const { return at_; }
  [[nodiscard]] std::size_t left() const { return bytes_.size() - at_; }

 private:
  void need(std::size_t n, const char* what) const {
    if (bytes_.size() - at_ < n) fail(std::string(what) + ": the file ends here");
  }

  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace eco::detail
