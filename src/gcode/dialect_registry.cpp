// The registry of dialects: Reader asks here for the front end of ReaderOptions::dialect.
#include "dialect_front_end.hpp"
#include "linuxcnc_front_end.hpp"

#include <fmt/format.h>

namespace kontur::gcode {

const char* to_string(Dialect dialect) noexcept {
  switch (dialect) {
    case Dialect::linuxcnc: return "linuxcnc";
  }
  return "?";
}

namespace detail {

std::unique_ptr<DialectFrontEnd> make_front_end(Dialect dialect, const DialectServices& services) {
  switch (dialect) {
    case Dialect::linuxcnc: return std::make_unique<LinuxcncFrontEnd>(services);
  }
  throw InputError("dialect", fmt::format("dialect {} is not implemented", static_cast<int>(dialect)));
}

}  // namespace detail
}  // namespace kontur::gcode
