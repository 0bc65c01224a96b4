#pragma once
// The fuzzer's bytes read as a sample would arrive: fixed-size fields copied raw (any double,
// NaN and infinities included; any integer), with what the DDS deserializer itself guarantees
// kept true (a bool is 0 or 1, a bounded string ends in NUL, a sequence's length matches its
// buffer). Past the end of the input every read yields zeros.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>

namespace grip::fuzz {

class FuzzBytes {
 public:
  FuzzBytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  template <typename T>
  requires std::is_trivially_copyable_v<T> T take()
  noexcept {
    T value{};
    copy(&value, sizeof value);
    return value;
  }
  bool take_bool() noexcept { return (take<std::uint8_t>() & 1U) != 0; }
  // Raw bytes into a fixed char field, NUL-terminated as a bounded string arrives.
  template <std::size_t N>
  void take_string(char (&out)[N]) noexcept {
    copy(out, N);
    out[N - 1] = '\0';
  }
  void copy(void* out, std::size_t n) noexcept {
    const std::size_t have = std::min(n, size_ - pos_);
    if (have > 0) std::memcpy(out, data_ + pos_, have);
    if (have < n) std::memset(static_cast<std::uint8_t*>(out) + have, 0, n - have);
    pos_ += have;
  }
  std::span<const std::uint8_t> rest() noexcept {
    const std::span<const std::uint8_t> r(data_ + pos_, size_ - pos_);
    pos_ = size_;
    return r;
  }
  std::size_t remaining() const noexcept { return size_ - pos_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace grip::fuzz
