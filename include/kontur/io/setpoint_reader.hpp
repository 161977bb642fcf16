#pragma once
// Reads setpoint files back (the CSV and binary formats of setpoint_writer.hpp, docs/setpoints.md),
// for `kontur verify`: the checker then proves them against a program and a machine, whoever
// wrote them.
#include <kontur/verify/checker.hpp>

#include <optional>
#include <string>
#include <vector>

namespace kontur {

/// The contents of a setpoint file.
struct SetpointFile {
  std::optional<double> period_s;        ///< servo period [s] (binary files carry it; CSV does not)
  std::vector<verify::Sample> samples;   ///< time [s], position [mm] and source line per setpoint
};

/// Reads a CSV (header `t,x,y,z,v,block`) or binary (`KONTURSP`) setpoint file; the format is
/// recognised by its first bytes. Throws InputError naming the file, the line (CSV) or record
/// (binary), the value and the rule for a missing file, a wrong header, a row without six numbers,
/// a truncated record or a wrong version.
[[nodiscard]] SetpointFile read_setpoints(const std::string& path);

}  // namespace kontur
