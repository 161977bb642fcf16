#pragma once
// Sinks for setpoints: CSV with a header line (columns t [s], x y z [mm], v [mm/s], block = source
// line), and a compact little-endian binary format for long runs (docs/setpoints.md). Both stream:
// one setpoint at a time, nothing held. Output is reproducible byte for byte.
#include <kontur/trajectory/sampler.hpp>

#include <cstdint>
#include <ostream>

namespace kontur {

/// Binary format: header "KONTURSP" (8 bytes), u32 version = 1, u32 record size = 48,
/// f64 servo period [s]; then one record per setpoint: f64 t [s], f64 x, y, z [mm],
/// f64 v [mm/s], i64 source line. All little-endian IEEE 754.
inline constexpr char setpoint_binary_magic[9] = "KONTURSP";
inline constexpr std::uint32_t setpoint_binary_version = 1;

/// Output format of setpoints.
enum class SetpointFormat { csv, binary };

/// Writes setpoints (positions in the X Y Z layout) to a stream in one of the formats. write() never allocates.
class SetpointWriter {
public:
  SetpointWriter(std::ostream& out, SetpointFormat format, double period_s);
  /// Writes one setpoint; in CSV, positions [mm] in the shortest form that reads back exactly, t [s]
  /// with 9 decimals, v [mm/s] with 6.
  void write(const trajectory::Setpoint& s);
  /// Setpoints written.
  [[nodiscard]] long count() const noexcept { return count_; }

private:
  std::ostream* out_;
  SetpointFormat format_;
  long count_ = 0;
};

}  // namespace kontur
