#pragma once
// Bounds-checked reads of a serialised record or message: little- or big-endian integers, with or
// without CDR's alignment (each value at a multiple of its size from the encapsulation's end).
// Every fault throws eco::io::Error naming the source and the byte.

#include <eco/io/error.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>

namespace eco::io::detail {

class ByteReader {
 public:
  /// `base`: what to add to an offset in `bytes` to name a byte of the source (a chunk's place in
  /// its file); `align_from`: CDR's alignment origin within `bytes`, or npos for none.
  ByteReader(std::span<const std::uint8_t> bytes, const std::string& source, std::size_t base = 0,
             std::size_t align_from = kUnaligned, bool big_endian = false)
      : bytes_(bytes), source_(source), base_(base), align_from_(align_from), big_endian_(big_endian) {}

  static constexpr std::size_t kUnaligned = std::size_t(-1);

  template <class T>
  [[nodiscard]] T read(const char* what) {
    static_assert(std::is_arithmetic_v<T>);
    align(sizeof(T));
    const std::span<const std::uint8_t> raw = take(sizeof(T), what);
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));
    if constexpr (sizeof(T) > 1) {
      if (big_endian_ != (std::endian::native == std::endian::big)) value = swapped(value);
    }
    return value;
  }

  /// `n` bytes as they are.
  [[nodiscard]] std::span<const std::uint8_t> take(std::uint64_t n, const char* what) {
    if (n > remaining()) {
      fail(std::string(what) + " needs " + std::to_string(n) + " bytes, " + std::to_string(remaining()) + " remain");
    }
    const std::span<const std::uint8_t> out = bytes_.subspan(at_, std::size_t(n));
    at_ += std::size_t(n);
    return out;
  }

  /// A uint32-length-prefixed string; CDR's counts and drops a closing NUL.
  [[nodiscard]] std::string string(const char* what) {
    const std::uint32_t length = read<std::uint32_t>(what);
    const std::span<const std::uint8_t> raw = take(length, what);
    std::size_t n = raw.size();
    if (align_from_ != kUnaligned && n > 0 && raw[n - 1] == 0) --n;
    return {reinterpret_cast<const char*>(raw.data()), n};
  }

  [[nodiscard]] std::size_t offset() const { return at_; }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - at_; }
  void seek(std::size_t offset) { at_ = offset; }

  [[noreturn]] void fail(const std::string& message) const { fail_at(at_, message); }
  [[noreturn]] void fail_at(std::size_t offset, const std::string& message) const {
    throw Error(source_, at_byte(base_ + offset), message);
  }

 private:
  void align(std::size_t size) {
    if (align_from_ == kUnaligned || at_ < align_from_) return;
    const std::size_t misplaced = (at_ - align_from_) % size;
    if (misplaced != 0) (void)take(size - misplaced, "padding");
  }

  template <class T>
  static T swapped(T value) {
    using U = std::conditional_t<sizeof(T) == 2, std::uint16_t, std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;
    U bits;
    std::memcpy(&bits, &value, sizeof(T));
    if constexpr (sizeof(T) == 2) bits = __builtin_bswap16(bits);
    if constexpr (sizeof(T) == 4) bits = __builtin_bswap32(bits);
    if constexpr (sizeof(T) == 8) bits = __builtin_bswap64(bits);
    std::memcpy(&value, &bits, sizeof(T));
    return value;
  }

  std::span<const std::uint8_t> bytes_;
  std::string source_;  // its own copy: a name built for one chunk would not outlive the call
  std::size_t base_;
  std::size_t align_from_;
  bool big_endian_;
  std::size_t at_ = 0;
};

}  // namespace eco::io::detail
