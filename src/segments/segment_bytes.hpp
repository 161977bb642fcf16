#pragma once
// Little-endian fields of the segment stream (docs/segments.md), written on any host.
#include <bit>
#include <cstdint>
#include <vector>

namespace kontur::segments::bytes {

inline void put_u32(std::uint8_t* p, std::uint32_t v) noexcept {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline void put_u16(std::uint8_t* p, std::uint16_t v) noexcept {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
/// An unsigned LEB128 varint appended to `out`.
inline void put_varint(std::vector<std::uint8_t>& out, std::uint32_t v) {
  while (v >= 0x80u) {
    out.push_back(static_cast<std::uint8_t>(v | 0x80u));
    v >>= 7;
  }
  out.push_back(static_cast<std::uint8_t>(v));
}
inline void put_u64(std::uint8_t* p, std::uint64_t v) noexcept {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline void put_f64(std::uint8_t* p, double v) noexcept { put_u64(p, std::bit_cast<std::uint64_t>(v)); }
inline void put_f32(std::uint8_t* p, float v) noexcept { put_u32(p, std::bit_cast<std::uint32_t>(v)); }
inline std::uint32_t get_u32(const std::uint8_t* p) noexcept {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

}  // namespace kontur::segments::bytes
