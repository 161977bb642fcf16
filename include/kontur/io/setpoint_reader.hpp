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
  AxisLayout layout = AxisLayout::xyz();  ///< the axes of its positions, in order
  std::vector<trajectory::Setpoint> samples;  ///< time [s], position [mm], speed [mm/s] and source line per setpoint
};

/// Receives each setpoint of a file in order (positions in the file's layout; no move id).
using SetpointVisitor = std::function<void(const trajectory::Setpoint&)>;

/// What a file's header says.
struct SetpointHeader {
  std::optional<double> period_s;         ///< servo period [s] (binary files carry it; CSV does not)
  AxisLayout layout = AxisLayout::xyz();  ///< the axes of the positions, in order
};
/// Receives the header before the first setpoint (it may throw to refuse the file before any
/// setpoint is read).
using HeaderVisitor = std::function<void(const SetpointHeader&)>;

/// Reads a setpoint file setpoint by setpoint, holding none (the same formats and errors as
/// read_setpoints; an error may come after earlier setpoints were visited). Returns the header,
/// which `header` (if set) also receives first.
SetpointHeader for_each_setpoint(const std::string& path, const SetpointVisitor& visit,
                                 const HeaderVisitor& header = {});

/// (A segment stream, `KONTURSG`, docs/segments.md, is replayed by the lower level.)
/// Reads a CSV (header `t,x,y,z,v,block`, or with more axes `t,x,y,z,a,v,block`: x y z and any
/// of a b c u v w in that order) or binary (`KONTURSP`, version 1 or 2) setpoint file; the format
/// is recognised by its first bytes. Throws InputError naming the file, the line (CSV) or record
/// (binary), the value and the rule for a missing file, a wrong header, a row without six numbers,
/// a truncated record or a wrong version.
[[nodiscard]] SetpointFile read_setpoints(const std::string& path);

}  // namespace kontur
