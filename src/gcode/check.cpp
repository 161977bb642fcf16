#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>

#include <fmt/format.h>

namespace kontur::gcode {

ProgramSummary check_program(const std::string& path, const ReaderOptions& options,
                             const std::function<void(const Block&, std::optional<double>)>& on_block) {
  Reader reader(path, options);
  ProgramSummary s;
  Block b;
  while (reader.next(b)) {
    const std::optional<double> len = b.length_mm();
    ++s.blocks;
    ++s.by_type[static_cast<std::size_t>(b.type)];
    if (!len) ++s.blocks_without_length;
    else if (b.type == BlockType::rapid) s.rapid_length_mm += *len;
    else s.path_length_mm += *len;
    s.dwell_s += b.dwell_s;
    if (on_block) on_block(b, len);
  }
  s.lines = reader.lines_read();
  s.warning_count = reader.warning_count();
  s.warnings = reader.warnings();
  s.dialect = reader.dialect();
  return s;
}

DialectChoice for_each_block(const std::string& path, const std::function<void(const Block&)>& on_block,
                             const ReaderOptions& options) {
  ReaderOptions again = options;
  DialectChoice choice;
  {
    Reader validate(path, options);  // pass 1: the whole program, no block kept
    Block b;
    while (validate.next(b)) {
      // The reader hands out the programmed contour under G41 / G42 (ModalState::cutter_comp); until
      // the compensation stage offsets it, a path of a cutter with a radius is refused, not run wrong.
      if (b.modal.cutter_comp != CutterComp::off && b.modal.cutter_radius_mm > 0.0 && b.type != BlockType::dwell)
        throw InputError("compensation-not-applied",
                         fmt::format("{}:{}:{}: cutter radius compensation ({}, radius {} mm) is read but not applied "
                                     "to the path yet (the offset contour is the compensation stage's, issue 15); "
                                     "`kontur check` shows the blocks",
                                     *b.location.file, b.location.line, b.location.column,
                                     b.modal.cutter_comp == CutterComp::left ? "G41" : "G42", b.modal.cutter_radius_mm));
    }
    again.dialect = validate.dialect().dialect;
    again.dialect_reason = validate.dialect().reason;
    choice = validate.dialect();
  }
  Reader reader(path, again);  // pass 2: the same program, now known to be valid
  Block b;
  while (reader.next(b)) on_block(b);
  return choice;
}

}  // namespace kontur::gcode
