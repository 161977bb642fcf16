#pragma once
// The G-code front end: a part program in, a stream of blocks out (docs/gcode.md has the syntax).
//
// Streaming: the Reader reads the program line by line through a fixed buffer and keeps only the
// modal state, the parameters and the spline being collected; its memory does not grow with the
// program's length.
//
// Errors: the first broken rule throws InputError("file:line:column: WORD: rule"). Because a
// reader streams, blocks before the error have already been handed out when it is found. The
// contract for later stages is therefore two passes: for_each_block() (and `kontur check`) first
// reads the whole program without keeping any block, and only if it is valid reads it again and
// hands the blocks out. A program with an error so yields no block to later stages.
#include <kontur/gcode/block.hpp>
#include <kontur/gcode/dialect.hpp>
#include <kontur/gcode/tool_table.hpp>
#include <kontur/tolerances.hpp>

#include <array>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kontur::gcode {

/// Reader settings.
struct ReaderOptions {
  /// Block delete switch: lines starting with '/' are skipped when true (the default), read when false.
  bool block_delete = true;
  /// Warnings kept in Reader::warnings() (the count goes on beyond).
  std::size_t max_warnings_kept = 100;
  /// O-word loop iterations and subroutine calls allowed in the whole program; more is an error
  /// (an endless loop). Default tolerances::gcode_max_loop_iterations.
  long max_loop_iterations = tolerances::gcode_max_loop_iterations;
  /// The program's dialect (last, so that positional initialisers of the fields above still work);
  /// none: detected from the program (detect_dialect).
  std::optional<Dialect> dialect;
  /// Why `dialect` was given, for messages and summaries (empty: "given").
  std::string dialect_reason;
  /// Folders searched, in order, for a subroutine in a file of its own (LinuxCNC: `o<name> call`
  /// of a subroutine the program does not define runs `name.ngc`, as LinuxCNC's
  /// [RS274NGC] SUBROUTINE_PATH); empty: the program's own folder.
  std::vector<std::string> subroutine_path;
  /// The absolute tolerance of a centre-format arc's two radii in a mm program [mm] and in an inch
  /// program [in] (LinuxCNC's INI [RS274NGC] CENTER_ARC_RADIUS_TOLERANCE_MM / _INCH); none:
  /// tolerances::gcode_arc_radius_absolute_mm / _inch, LinuxCNC's defaults.
  std::optional<double> arc_radius_tolerance_mm;
  std::optional<double> arc_radius_tolerance_inch;
  /// The tool table (lengths of G43 H, diameters of G41 D / G42 D; the Fanuc family's H and D
  /// registers); none: G43 applies length 0 (recorded) and G41 / G42 with a tool number are refused
  /// (G41.1 / G42.1 give the diameter in the block). G10 L1 / L10 / L11 change the run's copy.
  std::shared_ptr<const ToolTable> tool_table;
};

/// Reads a program and hands out its blocks one by one.
class Reader {
public:
  /// Opens the file `path`; throws InputError if it does not exist or is not a text file.
  explicit Reader(const std::string& path, ReaderOptions options = {});
  /// Reads the program from memory (`text`); `name` is used in messages. The text is copied.
  Reader(std::string_view name, std::string text, ReaderOptions options = {});
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  Reader(Reader&&) noexcept;
  Reader& operator=(Reader&&) noexcept;

  /// Next block into `out`; false at the end of the program (M2, M30, the closing '%' or the end of
  /// the file). Throws InputError at the first error.
  bool next(Block& out);
  /// Warnings so far ("file:line:column: message"), at most options.max_warnings_kept of them.
  [[nodiscard]] const std::vector<std::string>& warnings() const noexcept;
  /// Number of warnings so far (including those not kept).
  [[nodiscard]] std::size_t warning_count() const noexcept;
  /// Lines read so far.
  [[nodiscard]] long lines_read() const noexcept;
  /// The dialect the program is read in (ReaderOptions::dialect, or detected) and why.
  [[nodiscard]] const DialectChoice& dialect() const noexcept;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Totals of a checked program.
struct ProgramSummary {
  long lines = 0;                                  ///< lines read
  long blocks = 0;                                 ///< blocks handed out
  std::array<long, block_type_count> by_type{};    ///< blocks per BlockType
  double path_length_mm = 0.0;                     ///< length of all feed moves [mm] (conics not counted)
  double rapid_length_mm = 0.0;                    ///< length of all rapid moves [mm]
  double dwell_s = 0.0;                            ///< total dwell [s]
  long blocks_without_length = 0;                  ///< conic blocks, whose length is not known yet
  std::size_t warning_count = 0;                   ///< warnings
  std::vector<std::string> warnings;               ///< the first warnings
  DialectChoice dialect;                           ///< the dialect it was read in, and why
};

/// Reads the whole program and returns its totals; `on_block` (optional) sees every block with
/// its length (empty for a conic). Throws InputError at the first error.
ProgramSummary check_program(const std::string& path, const ReaderOptions& options = {},
                             const std::function<void(const Block&, std::optional<double>)>& on_block = {});

/// The later stages' entry: validates the whole program first (no block is handed out if it has an
/// error: InputError is thrown), then reads it again and calls `on_block` for every block.
/// Returns the dialect the program was read in. The same as validate_program, then
/// for_each_validated_block.
DialectChoice for_each_block(const std::string& path, const std::function<void(const Block&)>& on_block,
                             const ReaderOptions& options = {});

/// A program that the first pass found valid, and what the second pass reads it with.
struct ValidatedProgram {
  std::string path;
  ReaderOptions options;  ///< with the dialect the first pass read it in
  DialectChoice dialect;  ///< that dialect, and why
  /// The first pass's blocks, when they fit in tolerances::gcode_kept_blocks_bytes (kept_blocks
  /// true): the second pass hands them on instead of reading the program again. (A deque: kept
  /// as they come, none copied again as it grows.)
  std::deque<Block> blocks;
  bool kept_blocks = false;
};

/// The first pass alone: reads the whole program, throwing InputError at the first error. `seen`
/// (optional) sees every block of the valid part as it goes: to learn what the program does (which
/// axes it moves) before any block is handed on, without a pass of its own. The blocks are kept
/// for the second pass while they fit in tolerances::gcode_kept_blocks_bytes.
ValidatedProgram validate_program(const std::string& path, const ReaderOptions& options = {},
                                  const std::function<void(const Block&)>& seen = {});

/// The second pass alone: calls `on_block` for every block of a validated program (its kept blocks,
/// else read again).
void for_each_validated_block(const ValidatedProgram& program, const std::function<void(const Block&)>& on_block);

}  // namespace kontur::gcode
