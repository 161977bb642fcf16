#pragma once
// Internal to `kontur compress`: the program's text line by line (what is copied byte for byte),
// the tests on a line's words the compressor needs, and the writer of a run's new blocks in a
// dialect's words.
#include <kontur/compress/piece_fit.hpp>
#include <kontur/gcode/block.hpp>
#include <kontur/gcode/dialect.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace kontur::compress::detail {

/// The program's text, split into lines that keep their line ends.
class ProgramText {
 public:
  ProgramText(const std::string& path, gcode::Dialect dialect);
  [[nodiscard]] std::size_t line_count() const noexcept { return lines_.size(); }
  /// Line `line` (1-based) with its line end.
  [[nodiscard]] std::string_view line(long line) const noexcept { return lines_[static_cast<std::size_t>(line - 1)]; }
  /// The line end the program uses ("\r\n" or "\n").
  [[nodiscard]] const std::string& eol() const noexcept { return eol_; }
  [[nodiscard]] std::size_t size() const noexcept { return text_.size(); }
  /// True if line `line` holds nothing but a G1 move: the words N, G1 (G01), X, Y, Z and F with
  /// numbers, parameters or expressions; no comment, no other letter, no block delete.
  [[nodiscard]] bool plain_feed_line(long line) const;
  /// The line's N number ("N120"), or empty.
  [[nodiscard]] std::string n_word(long line) const;
  /// True if a line after `line` may move with the modal motion mode before a motion code is
  /// programmed again (an axis word without G0..G3 or a cycle; or control flow, which may jump
  /// anywhere): the run that ends on `line` must leave the motion mode G1.
  [[nodiscard]] bool next_lines_need_g1(long line) const;

 private:
  [[nodiscard]] std::string code_of(long line) const;  // upper case, comments removed
  std::string text_;
  std::vector<std::string_view> lines_;
  std::string eol_ = "\n";
  gcode::Dialect dialect_;
};

/// What a run became in text.
struct WrittenRun {
  std::string text;       ///< the lines, each with the program's line end
  std::size_t lines = 0;  ///< how many
  /// For each piece its lines in `text` (0-based first and last; the plane or G91 restored after
  /// the last piece belongs to none).
  std::vector<std::pair<std::size_t, std::size_t>> piece_lines;
};

/// Writes a run's pieces as blocks of `dialect`, in the program's units and coordinates.
class RunWriter {
 public:
  /// `modal`: the state the run's lines were read in (units, G90/G91, G90.1, plane);
  /// `tolerance_mm`: sets the decimals (at least tolerances::compress_decimals_mm / _inch).
  RunWriter(gcode::Dialect dialect, const ProgramText& text, const gcode::ModalState& modal, double tolerance_mm);
  /// The blocks of `pieces` over `vertices` (program coordinates [mm]), at `feed_mm_min`; the first
  /// block carries the N number of `first_line`.
  [[nodiscard]] WrittenRun write(const std::vector<Vec3>& vertices, const std::vector<Piece>& pieces,
                                 double feed_mm_min, long first_line);

 private:
  [[nodiscard]] std::string number(double program_value, int decimals) const;
  // Axis words of `target` [mm] that differ from the position (all three if `all`); updates it.
  std::string axes(const Vec3& target_mm, bool all, bool exact = false);
  void block(std::string words);
  gcode::Dialect dialect_;
  const ProgramText& text_;
  gcode::ModalState modal_;
  double unit_ = 1.0;  // mm per program unit
  int decimals_ = 4;
  bool decimal_point_ = false;  // the Fanuc family reads "X3" as 3 increments: always a point
  Vec3 position_ = Vec3::Zero();  // where the control is [program units]
  std::string prefix_;
  WrittenRun out_;
};

}  // namespace kontur::compress::detail
