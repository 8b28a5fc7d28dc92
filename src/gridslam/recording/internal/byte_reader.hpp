// Bounds-checked little/big-endian reader over a byte buffer, shared by the ROS 1 bag, MCAP and
// message decoders. Every read past the end sets a sticky failure flag and returns zeros, so
// decoders check ok() once after a message instead of after every field.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace gridslam::recording::internal {

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes, bool big_endian = false)
      : bytes_(bytes), big_endian_(big_endian) {}

  [[nodiscard]] bool ok() const { return ok_; }
  [[nodiscard]] std::size_t position() const { return pos_; }
  [[nodiscard]] std::size_t remaining() const { return ok_ ? bytes_.size() - pos_ : 0; }
  [[nodiscard]] bool AtEnd() const { return !ok_ || pos_ >= bytes_.size(); }
  void Fail() { ok_ = false; }

  /// Skips padding so that the position (relative to `origin`) is a multiple of `n`.
  void Align(std::size_t n, std::size_t origin = 0) {
    const std::size_t rel = pos_ - origin;
    const std::size_t pad = (n - rel % n) % n;
    Skip(pad);
  }
  void Skip(std::size_t n) {
    if (!ok_ || n > bytes_.size() - pos_) {
      ok_ = false;
      return;
    }
    pos_ += n;
  }
  /// The next n bytes (empty and failed if fewer remain).
  std::span<const std::uint8_t> Bytes(std::size_t n) {
    if (!ok_ || n > bytes_.size() - pos_) {
      ok_ = false;
      return {};
    }
    auto out = bytes_.subspan(pos_, n);
    pos_ += n;
    return out;
  }
  std::span<const std::uint8_t> Rest() { return Bytes(remaining()); }

  template <class T>
  T Read() {
    static_assert(std::is_trivially_copyable_v<T>);
    auto b = Bytes(sizeof(T));
    if (b.empty()) {
      return T{};
    }
    std::uint8_t tmp[sizeof(T)];
    std::memcpy(tmp, b.data(), sizeof(T));
    if (big_endian_) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
        std::swap(tmp[i], tmp[sizeof(T) - 1 - i]);
      }
    }
    T value;
    std::memcpy(&value, tmp, sizeof(T));
    return value;
  }
  std::uint8_t U8() { return Read<std::uint8_t>(); }
  std::uint16_t U16() { return Read<std::uint16_t>(); }
  std::uint32_t U32() { return Read<std::uint32_t>(); }
  std::uint64_t U64() { return Read<std::uint64_t>(); }
  std::int32_t I32() { return Read<std::int32_t>(); }
  float F32() { return Read<float>(); }
  double F64() { return Read<double>(); }

  /// n bytes as a string.
  std::string String(std::size_t n) {
    auto b = Bytes(n);
    return {reinterpret_cast<const char*>(b.data()), b.size()};
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  bool ok_ = true;
  bool big_endian_ = false;
};

inline std::span<const std::uint8_t> AsBytes(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

}  // namespace gridslam::recording::internal
