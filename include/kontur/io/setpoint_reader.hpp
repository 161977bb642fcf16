#pragma once
// Reads setpoint files back (the CSV and binary formats of setpoint_writer.hpp, docs/setpoints.md),
// for `kontur verify`: the checker then proves them against a program and a machine, whoever
// wrote them.
#include <kontur/trajectory/sampler.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kontur {

/// The contents of a setpoint file.
struct SetpointFile {
  std::optional<double> period_s;        ///< servo period [s] (binary files carry it; CSV does not)
  std::vector<trajectory::Setpoint> samples;  ///< time [s], position [mm], speed [mm/s] and source line per setpoint
};

/// Receives each setpoint of a file in order (positions X Y Z; no move id).
using SetpointVisitor = std::function<void(const trajectory::Setpoint&)>;

/// Receives the servo period [s] of a binary file's header, before its first setpoint (it may
/// throw to refuse the file before any setpoint is read).
using PeriodVisitor = std::function<void(double period_s)>;

/// Reads a setpoint file setpoint by setpoint, holding none (the same formats and errors as
/// read_setpoints; an error may come after earlier setpoints were visited). Returns the servo
/// period [s] a binary file carries (none for CSV), which `period` (if set) also receives first.
std::optional<double> for_each_setpoint(const std::string& path, const SetpointVisitor& visit,
                                        const PeriodVisitor& period = {});

/// Reads a CSV (header `t,x,y,z,v,block`) or binary (`KONTURSP`) setpoint file; the format is
/// recognised by its first bytes. Throws InputError naming the file, the line (CSV) or record
/// (binary), the value and the rule for a missing file, a wrong header, a row without six numbers,
/// a truncated record or a wrong version.
[[nodiscard]] SetpointFile read_setpoints(const std::string& path);

}  // namespace kontur
