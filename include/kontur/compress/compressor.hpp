#pragma once
// `kontur compress`: a part program in, the same program out with its runs of G1 lines replaced by
// fewer blocks (lines, G2/G3 arcs, 3-D arcs, conics, splines: compress/piece_fit.hpp) that stay
// within a tolerance of the programmed lines. Everything else (rapids, the modal state, comments,
// tool changes, control flow, every line that is not part of a run) is copied byte for byte.
//
// A run is a sequence of consecutive source lines of the main file, each a plain G1 block (only
// N, G1, X, Y, Z and F words, values and expressions allowed; no comment, no other word), executed
// exactly once (not in a loop or a called subroutine executed twice), at one feed, in one modal
// state and one coordinate frame (translation and rotation only), without cutter compensation and
// without moving an extra axis. The new blocks are written in the program's coordinates and units
// (G90: absolute, G91: within G90 ... G91), the plane (G17/G18/G19) and motion mode restored where
// the program relies on them.
//
// The result is checked apart from the fit: the written program is read again, and for every run
// the distance of each new piece (sampled) from its programmed lines, and of every programmed vertex
// from the new piece, must be within the tolerance; a piece that is not is written as its lines,
// and the whole is checked again. The blocks outside the runs must come out the same as before.
#include <kontur/compress/piece_fit.hpp>
#include <kontur/gcode/reader.hpp>

#include <array>
#include <string>
#include <vector>

namespace kontur::compress {

/// Settings of a compression.
struct CompressOptions {
  double tolerance_mm = 0.01;  ///< largest deviation from the programmed lines, both ways [mm]
  CurveKinds kinds;            ///< the curves the output may use (default_kinds of the dialect)
  gcode::ReaderOptions reader; ///< how the program is read (its dialect must be set)
};

/// The curves a dialect's control reads: arcs everywhere; 3-D arcs for Fanuc and Mitsubishi
/// (G02.4) and Sinumerik (CIP); splines for LinuxCNC (G6.2) and Fanuc and Mitsubishi (G06.2);
/// conics never (Kontur's CONIC block is read by Kontur only: ask for them).
[[nodiscard]] CurveKinds default_kinds(gcode::Dialect dialect) noexcept;

/// What became of one run.
struct RunReport {
  long first_line = 0, last_line = 0;  ///< the run's source lines in the input (1-based)
  long output_line = 0;                ///< its first line in the output (1-based)
  std::size_t lines_in = 0;            ///< G1 blocks it had
  std::size_t blocks_out = 0;          ///< lines written in their place
  std::array<std::size_t, 5> pieces{}; ///< pieces per PieceKind
  double deviation_mm = 0.0;           ///< the check's largest distance, both ways [mm]
  std::string kept;                    ///< empty, or why the run was written as it was
};

/// The result of a compression.
struct CompressResult {
  std::string text;                 ///< the output program
  gcode::DialectChoice dialect;     ///< the dialect it was read and written in
  std::vector<RunReport> runs;      ///< every run found, in order
  std::size_t feed_blocks_in = 0;   ///< feed blocks of the input (each G1, G2, CONIC, spline, ...)
  std::size_t feed_blocks_out = 0;  ///< of the output (a spline: a block per control point and knot line)
  std::size_t input_blocks = 0;     ///< all blocks of the input
  double max_deviation_mm = 0.0;    ///< largest deviation of a compressed run [mm]
  std::size_t pieces_rewritten = 0; ///< pieces the check found out of tolerance, written as their lines
};

/// Compresses the program `path`. Throws InputError for a program Kontur cannot read, or a
/// tolerance that is not a positive finite number.
[[nodiscard]] CompressResult compress_program(const std::string& path, const CompressOptions& options);

}  // namespace kontur::compress
