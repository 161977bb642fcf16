// The registry of dialects: Reader asks here for the front end of the program's dialect and for
// the rules its executor follows.
#include "dialect_front_end.hpp"
#include "fanuc_front_end.hpp"
#include "linuxcnc_front_end.hpp"
#include "sinumerik_front_end.hpp"

#include <fmt/format.h>

namespace kontur::gcode::detail {

DialectRules rules_of(Dialect dialect) noexcept {
  DialectRules r;
  switch (dialect) {
    case Dialect::fanuc:
    case Dialect::haas:
    case Dialect::mitsubishi:
      r.fanuc_offset_registers = true;
      [[fallthrough]];
    case Dialect::mach3:
      r.g80_restores_motion = true;
      r.motion_code_beside_nonmodal = true;
      r.fanuc_cycles = true;
      break;
    case Dialect::linuxcnc: r.linuxcnc_polar = true; break;
    case Dialect::sinumerik:
    case Dialect::grbl: break;
  }
  return r;
}

std::unique_ptr<DialectFrontEnd> make_front_end(Dialect dialect, const DialectServices& services) {
  switch (dialect) {
    case Dialect::linuxcnc:
    case Dialect::grbl: return std::make_unique<LinuxcncFrontEnd>(services);
    case Dialect::fanuc:
    case Dialect::haas:
    case Dialect::mitsubishi:
    case Dialect::mach3: return std::make_unique<FanucFrontEnd>(services);
    case Dialect::sinumerik: return std::make_unique<SinumerikFrontEnd>(services);
  }
  throw InputError("dialect", fmt::format("{}: the {} dialect is not implemented yet", services.diagnostics.context().file,
                                          to_string(dialect)));
}

}  // namespace kontur::gcode::detail
