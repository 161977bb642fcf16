#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/tolerances.hpp>

#include <variant>

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

namespace {

// The memory a block takes [bytes]: itself and a spline's arrays.
std::size_t block_bytes(const Block& b) {
  std::size_t n = sizeof(Block);
  if (const auto* nurbs = std::get_if<NurbsCurve>(&b.geometry))
    n += 2 * (nurbs->knots().size() * sizeof(double) + nurbs->points().size() * sizeof(Vec3) +
              nurbs->weights().size() * sizeof(double));  // (and its span polynomials, about as much)
  return n;
}

}  // namespace

ValidatedProgram validate_program(const std::string& path, const ReaderOptions& options,
                                  const std::function<void(const Block&)>& seen) {
  Reader validate(path, options);  // the whole program: an error anywhere stops here
  ValidatedProgram v{path, options, {}, {}, true};
  std::size_t kept_bytes = 0;
  Block b;
  while (validate.next(b)) {  // every block, compensated
    if (seen) seen(b);
    if (!v.kept_blocks) continue;
    kept_bytes += block_bytes(b);
    if (kept_bytes <= tolerances::gcode_kept_blocks_bytes) {
      v.blocks.push_back(std::move(b));  // (next() assigns it anew)
    } else {  // too long to keep: the second pass reads it again
      v.kept_blocks = false;
      std::deque<Block>().swap(v.blocks);
    }
  }
  v.dialect = validate.dialect();
  v.options.dialect = v.dialect.dialect;
  v.options.dialect_reason = v.dialect.reason;
  return v;
}

void for_each_validated_block(const ValidatedProgram& program, const std::function<void(const Block&)>& on_block) {
  if (program.kept_blocks) {
    for (const Block& b : program.blocks) on_block(b);
    return;
  }
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
