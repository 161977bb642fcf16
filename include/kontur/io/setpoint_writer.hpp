#pragma once
// Sinks for setpoints: CSV with a header line (columns t [s], x y z [mm], v [mm/s], block = source
// line), and a compact little-endian binary format for long runs (docs/setpoints.md). Both stream:
// one setpoint at a time, nothing held. Output is reproducible byte for byte.
#include <kontur/trajectory/sampler.hpp>

#include <cstdint>
#include <ostream>

namespace kontur {

/// Binary format: header "KONTURSP" (8 bytes), u32 version, u32 record size, f64 servo period [s];
/// version 1 (X Y Z layouts): records of 48 bytes, f64 t [s], f64 x, y, z [mm], f64 v [mm/s],
/// i64 source line. Version 2 (any other layout): after the period, u32 axis count n and 12 bytes
/// of axis letters (upper case, in order, zero-padded); records of 8 (n + 3) bytes: f64 t [s], n
/// f64 positions [mm] or [deg], f64 v [mm/s], i64 source line. All little-endian IEEE 754.
inline constexpr char setpoint_binary_magic[9] = "KONTURSP";
inline constexpr std::uint32_t setpoint_binary_version = 1;
inline constexpr std::uint32_t setpoint_binary_version_axes = 2;

/// Bytes of a binary setpoint file of `count` setpoints in `layout`: its header (24 bytes in
/// version 1, 40 in version 2) and 8 (n + 3) bytes per setpoint.
[[nodiscard]] std::uint64_t binary_setpoint_bytes(const AxisLayout& layout, std::uint64_t count) noexcept;

/// Output format of setpoints.
enum class SetpointFormat { csv, binary };

/// Writes setpoints to a stream in one of the formats, one column per axis of the layout (CSV:
/// `t,x,y,z,v,block` for X Y Z, `t,x,y,z,a,v,block` with an A axis, ...). write() never allocates.
class SetpointWriter {
public:
  SetpointWriter(std::ostream& out, SetpointFormat format, double period_s, const AxisLayout& layout = AxisLayout::xyz());
  /// Writes one setpoint; in CSV, positions [mm] in the shortest form that reads back exactly, t [s]
  /// with 9 decimals, v [mm/s] with 6.
  void write(const trajectory::Setpoint& s);
  /// Setpoints written.
  [[nodiscard]] long count() const noexcept { return count_; }

private:
  std::ostream* out_;
  SetpointFormat format_;
  int axes_ = 3;
  long count_ = 0;
};

}  // namespace kontur
