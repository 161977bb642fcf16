#pragma once
// Kontur's main job as one library call: a part program and a machine in; setpoints out to a sink
// as they are made; the independent check (and a report's observer) fed as they stream; the JSON
// summary built at the end. The stages, in the one direction the data flows:
//   gcode::Reader -> program::ProgramPath (moves, corner blends, dwells, move ids)
//   -> plan::MotionPlanner (look-ahead, S-curves) -> trajectory::Trajectory (time segments)
//   -> trajectory::Sampler (setpoints at the servo period) -> sinks and verify::Checker.
// `kontur run` and `kontur verify`, the shared-program tests and the benchmarks all call this;
// nothing retypes it.
#include <functional>
#include <kontur/axes.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/machine.hpp>
#include <kontur/program/move.hpp>
#include <kontur/program/program_path.hpp>
#include <kontur/trajectory/sampler.hpp>
#include <kontur/verify/checker.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kontur {

/// How a program is run.
struct PipelineOptions {
  bool blend = true;          ///< blend corners within the G64 tolerance (false: `--no-blend`)
  bool smooth = true;         ///< smooth runs of dense lines within the G64 tolerance (false: `--no-smooth`)
  bool check = true;          ///< check the setpoints independently as they stream (false: planning only)
  bool time_optimal = false;  ///< add the time-optimal reference (acceleration-limited) to the summary
  /// Setpoints carry their exact velocity and acceleration (Setpoint::velocity, for the segment stream).
  bool derivatives = false;
  /// How the program is read: block delete, dialect (none: the machine's, else detected).
  gcode::ReaderOptions reader;
};

/// What a run hands out while it goes. Every handler may be empty.
struct PipelineEvents {
  std::function<void(const trajectory::Setpoint&)> setpoint;  ///< each setpoint, in order
  verify::Observer observer;                                  ///< the checker's measures of each setpoint
  std::function<void(long line)> progress;                    ///< after each block: its source line
};

/// The outcome of a run or of a check of a setpoint file.
struct RunResult {
  verify::Report check;       ///< the independent check (empty when options.check is false)
  long setpoints = 0;         ///< setpoints made (or read)
  double total_time_s = 0.0;  ///< time of the last setpoint [s]
  std::string summary_json;   ///< the JSON summary (report/summary.hpp; empty when options.check is false)
  /// True when the check found every limit held.
  bool passed = false;
};

/// How a program is to be read, as a user gives it: the command's --dialect, --no-block-delete,
/// --subroutine-path and --tool-table, the Python module's keywords of the same names.
struct ProgramReading {
  std::optional<gcode::Dialect> dialect;  ///< none: the machine's, else detected from the program
  std::string given_reason = "given with --dialect";  ///< why, when `dialect` is given
  bool block_delete = true;                  ///< skip lines starting with '/'
  std::vector<std::string> subroutine_path;  ///< folders of subroutine files (empty: the machine's)
  std::string tool_table;                    ///< tool table file (empty: the machine file's, if any)
};

/// The reader options for `program` on `machine` (may be null: then no machine's dialect and the
/// tool table in [mm]): the dialect given, else the machine's, else detected from the program
/// (gcode::choose_dialect), with the reason; the tool table read in the machine's linear units.
/// A program that cannot be opened gets no dialect here (the reader reports it). Throws
/// InputError for a broken tool table.
[[nodiscard]] gcode::ReaderOptions program_reader_options(const std::string& program, const ProgramReading& reading,
                                                          const Machine* machine);

class Pipeline {
 public:
  /// Runs on `machine` (copied; validated by its reader) with `options`.
  explicit Pipeline(Machine machine, PipelineOptions options = {});
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  /// The axis layout of `program`'s setpoints, for a sink's header before run(): X Y Z, then the
  /// machine's A B C U V W that the program moves. It reads the program once, validating it (an
  /// error throws InputError here), and the next run() of the same program only reads it again
  /// to hand its blocks on (run() calls it if not called for the same program).
  const AxisLayout& prepare(const std::string& program);
  /// Reads, plans and samples `program` (a file path; a program with an error yields no setpoint:
  /// InputError is thrown before the first one), handing every setpoint to events.setpoint.
  RunResult run(const std::string& program, const PipelineEvents& events = {});

  /// Checks the setpoint file `setpoints` (CSV or binary, io/setpoint_reader.hpp) against
  /// `program` on the machine, streaming. Throws InputError for a program without motion, a file
  /// without setpoints, or a binary file written at another servo period.
  RunResult verify(const std::string& program, const std::string& setpoints, const PipelineEvents& events = {});
  /// Where verify() takes setpoints from: it calls `header` once (the axes, and the period if the
  /// source has one), then `visit` for each setpoint in order. A file (io/setpoint_reader.hpp), or
  /// setpoints held in memory (the Python module's arrays).
  using SetpointSource = std::function<void(const HeaderVisitor& header, const SetpointVisitor& visit)>;
  /// The same check of the setpoints `source` gives; `source_name` names them in messages and in
  /// the summary's "setpoint_file".
  RunResult verify(const std::string& program, const std::string& source_name, const SetpointSource& source,
                   const PipelineEvents& events = {});

  /// The moves of the path of the current or last run or verify, in order (moves()[id].id == id);
  /// the same vector for the pipeline's life (it grows while a run streams).
  [[nodiscard]] const std::vector<program::Move>& moves() const noexcept { return path_.moves(); }
  /// The machine.
  [[nodiscard]] const Machine& machine() const noexcept { return machine_; }
  /// The setpoints' axis layout.
  [[nodiscard]] const AxisLayout& layout() const noexcept { return layout_; }

 private:
  // options.reader, with the machine's dialect when it names none.
  [[nodiscard]] gcode::ReaderOptions reader_options() const;

  Machine machine_;
  PipelineOptions options_;
  AxisLayout layout_ = AxisLayout::xyz();
  std::optional<gcode::ValidatedProgram> prepared_;  // the program prepare() validated, for run()
  std::string prepared_stamp_;                       // its file's size and time then
  program::ProgramPath path_;
};

}  // namespace kontur
