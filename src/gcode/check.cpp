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

ValidatedProgram validate_program(const std::string& path, const ReaderOptions& options,
                                  const std::function<void(const Block&)>& seen) {
  Reader validate(path, options);  // the whole program, no block kept
  Block b;
  while (validate.next(b))  // every block, compensated: an error anywhere stops here
    if (seen) seen(b);
  ValidatedProgram v{path, options, validate.dialect()};
  v.options.dialect = v.dialect.dialect;
  v.options.dialect_reason = v.dialect.reason;
  return v;
}

void for_each_validated_block(const ValidatedProgram& program, const std::function<void(const Block&)>& on_block) {
  Reader reader(program.path, program.options);  // the same program, now known to be valid
  Block b;
  while (reader.next(b)) on_block(b);
}

DialectChoice for_each_block(const std::string& path, const std::function<void(const Block&)>& on_block,
                             const ReaderOptions& options) {
  const ValidatedProgram v = validate_program(path, options);
  for_each_validated_block(v, on_block);
  return v.dialect;
}

}  // namespace kontur::gcode
