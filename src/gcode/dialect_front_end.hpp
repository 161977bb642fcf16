#pragma once
// Internal: the seam between a G-code dialect and the dialect-neutral executor.
//
// A dialect front end turns the program's lines into the words of blocks (detail::Words): it knows
// how its dialect spells comments, block delete, line numbers, parameters and expressions, and
// it runs the dialect's control flow (LinuxCNC O-words; Fanuc GOTO / WHILE, Sinumerik labels and
// GOTOF would be theirs) by seeking in the ProgramInput. The executor (executor.hpp) then runs
// the words: modal state, frames and geometry, the same for every dialect.
//
// To add a dialect: a value in kontur::gcode::Dialect (reader.hpp), a class derived from
// DialectFrontEnd (e.g. fanuc_front_end.hpp/.cpp), and its case in make_front_end
// (dialect_registry.cpp). docs/gcode.md, "Dialects", says the same for users.
#include "block_words.hpp"
#include "diagnostics.hpp"
#include "program_input.hpp"

#include <kontur/gcode/expression.hpp>
#include <kontur/gcode/reader.hpp>

#include <memory>
#include <string_view>

namespace kontur::gcode::detail {

/// What a dialect's control flow asks of the executor.
class ControlFlowBarrier {
public:
  /// A control-flow line is about to run at `column` (it may jump): a multi-block construct still
  /// open (a spline being collected) is closed, or rejected if it cannot be.
  virtual void before_control_flow(int column) = 0;

protected:
  ~ControlFlowBarrier() = default;
};

/// Where a dialect's control differs from LinuxCNC's in running words (the executor's part; how
/// the words are spelled is the front end's).
struct DialectRules {
  /// G80 cancels only the canned cycle: the G0 / G1 / G2 / G3 in effect before it is the motion
  /// mode again (Fanuc group 01 and group 09 are apart), instead of "no motion mode" (LinuxCNC).
  bool g80_restores_motion = false;
  /// A motion code (G0..G3) beside G28 / G30 / G92 / G10 only sets the motion mode; the block's axis
  /// words are the non-modal code's (Fanuc's "G0 G91 G28 Z0"). LinuxCNC refuses the block.
  bool motion_code_beside_nonmodal = false;
  /// The Fanuc family's drilling cycles G84 (tapping, as feed in and out), G85, G86 and G89 are
  /// expanded, and K in a cycle block is its repeat count (L); LinuxCNC refuses G84-G89.
  bool fanuc_cycles = false;
  /// Polar coordinates are LinuxCNC's `@ ^`: about the XY origin of the program coordinates, in G17
  /// only; in G91 both add to the current point's radius and angle. Else Sinumerik's AP= / RP=
  /// about the pole (G110-G112), in any plane.
  bool linuxcnc_polar = false;
  /// The Fanuc family's offset registers: G10 L10 / L11 P n R set the length (geometry / wear) of
  /// H n, G10 L12 / L13 the radius of D n (wear is added to the geometry); H n and D n read tool n of
  /// the tool table (its length, half its diameter). Else LinuxCNC's G10 L10 / L11 (the tool entry
  /// from the current position).
  bool fanuc_offset_registers = false;
};
/// The rules of `dialect` (dialect_registry.cpp).
[[nodiscard]] DialectRules rules_of(Dialect dialect) noexcept;

/// What a dialect's system variables read of the executor, and the few it writes (Fanuc's #4001..,
/// #5001.., #5221..). Lengths in [mm] (the front end converts to the program's units).
class ExecutorState {
public:
  /// The modal state now.
  [[nodiscard]] virtual const ModalState& modal_state() const noexcept = 0;
  /// The end point of the last block, in program coordinates [mm].
  [[nodiscard]] virtual const Vec3& position() const noexcept = 0;
  /// The same point in machine coordinates [mm].
  [[nodiscard]] virtual Vec3 machine_position() const = 0;
  /// The last G0 / G1 / G2 / G3 (0..3; 0 before any), Fanuc's group 01 apart from the cycles.
  [[nodiscard]] virtual int group01_code() const noexcept = 0;
  /// The feed in effect [mm/min].
  [[nodiscard]] virtual double feed_rate() const noexcept = 0;
  /// The offset of work system `system` (1 = G54 .. 9 = G59.3) [mm].
  [[nodiscard]] virtual Vec3 work_offset(int system) const = 0;
  /// The G92 offset [mm] (LinuxCNC's and Mach3's #5211-#5213).
  [[nodiscard]] virtual Vec3 g92_offset() const = 0;
  /// Sets one axis (0 X, 1 Y, 2 Z) of the offset of work system `system` [mm], as G10 L2 does.
  virtual void set_work_offset(int system, int axis, double mm) = 0;

protected:
  ~ExecutorState() = default;
};

/// Everything a front end works with; owned by the Reader and outliving the front end.
struct DialectServices {
  Dialect dialect;                ///< the dialect being read (one front end may serve several)
  ProgramInput& input;            ///< the program text (read_line, seek)
  ParameterTable& parameters;     ///< the program's parameters
  Diagnostics& diagnostics;       ///< file, line, errors and warnings
  const ReaderOptions& options;   ///< block delete, loop limit
  ControlFlowBarrier& executor;   ///< told before control flow runs
  ExecutorState* state = nullptr; ///< the executor's state, for system variables (Fanuc)
};

/// What one line of the program turned into.
enum class LineOutcome {
  nothing,      ///< no block: empty, a comment, a deleted block, an assignment or control flow
  words,        ///< the words of a block, to be run by the executor
  program_end,  ///< the dialect's own end of program (LinuxCNC: the closing '%')
};

/// One dialect's lexing and control flow.
class DialectFrontEnd {
public:
  virtual ~DialectFrontEnd() = default;
  /// Which dialect this is.
  [[nodiscard]] virtual Dialect dialect() const noexcept = 0;
  /// Reads the line `raw` (just read from the input, without its end of line): fills `words` and
  /// returns LineOutcome::words for a block, runs control flow or assignments otherwise.
  virtual LineOutcome read_line(std::string_view raw, Words& words) = 0;
  /// A line that expands into several blocks (a Sinumerik drilling cycle) hands the blocks after
  /// the first here, one per call, after the previous one ran; false when there is none left.
  virtual bool pending_words(Words& words) {
    (void)words;
    return false;
  }
  /// The input has ended: throws if control flow is left open (a sub, loop or if without its end).
  virtual void at_end_of_input() = 0;
  /// True if the program marked its own end (LinuxCNC: it started with '%'), so that a missing
  /// M2 / M30 is not worth a warning.
  [[nodiscard]] virtual bool program_marks_its_end() const noexcept = 0;
};

/// The front end of `dialect` (dialect_registry.cpp).
[[nodiscard]] std::unique_ptr<DialectFrontEnd> make_front_end(Dialect dialect, const DialectServices& services);

}  // namespace kontur::gcode::detail
