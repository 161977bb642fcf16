// `kontur run PROGRAM`: Kontur's main job, the library's Pipeline (kontur/pipeline.hpp). The
// program's blocks (validated first: a program with an error yields no setpoint) are planned on
// the machine and sampled at its servo period; the setpoints go to a CSV or binary file (or
// stdout) as they are made, checked independently on the way, and a JSON summary follows.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/io/setpoint_writer.hpp>
#include <kontur/machine.hpp>
#include <kontur/pipeline.hpp>
#include <kontur/segments/segment_stream.hpp>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "interrupt.hpp"
#include "program_options.hpp"
#include "report_output.hpp"
#include "run_report.hpp"
#include "summary_output.hpp"

namespace kontur::app {
namespace {

struct RunOptions {
  std::string program;
  std::string machine;
  std::string output;  // none: no setpoints written
  std::string format = "csv";
  double segment_tolerance_mm = tolerances::segment_tolerance_mm;
  std::string summary;
  bool time_optimal = false;
  std::string report;
  bool quiet = false;
  bool json = false;
  bool no_blend = false;
  bool no_smooth = false;
  ProgramReadOptions read;
};

// A progress bar on stderr for runs longer than a second, only when stderr is a terminal (and
// not --quiet). Redrawn at most ten times a second; erased at the end.
class Progress {
 public:
  explicit Progress(bool enabled) : enabled_(enabled && isatty(fileno(stderr)) != 0) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { clear(); }
  [[nodiscard]] bool enabled() const noexcept { return enabled_; }
  /// `fraction` of `phase` done.
  void update(const char* phase, double fraction, const std::string& detail) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    constexpr int width = 30;
    const int filled = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * width);
    std::fprintf(stderr, "\r\033[Kkontur run: %-8s [%s%s] %3d%% %s", phase, std::string(filled, '#').c_str(),
                 std::string(width - filled, ' ').c_str(), static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100),
                 detail.c_str());
    std::fflush(stderr);
    drawn_ = true;
  }
  void clear() {
    if (!drawn_) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
  }

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

// Lines of a text file (for the progress bar; 0 if it cannot be read: the reader reports that).
long count_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  long n = 1;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    n += static_cast<long>(std::count(buf, buf + in.gcount(), '\n'));
    if (!in) break;
  }
  return n;
}

bool run_program(const RunOptions& o) {
  // Where each output goes; the standard output carries at most one of them.
  const SummaryOutputs summaries{o.summary, o.json, o.quiet, o.output == "-" || o.report == "-"};
  const bool json_stdout = summaries.json_on_stdout();
  const bool setpoints = !o.output.empty();
  // The report path is checked before any work: not an input, not the setpoint file.
  std::vector<std::filesystem::path> inputs = {o.program};
  if (!o.machine.empty()) inputs.emplace_back(o.machine);
  if (!o.report.empty()) {
    if (o.report == "-" && o.output == "-")
      throw CLI::ValidationError("--report", "--report - needs -o FILE or no -o: the setpoints already go to the standard output");
    if (o.report != "-") {
      check_output_not_input(o.report, inputs);
      if (setpoints && o.output != "-") check_output_not_input(o.report, {o.output});
    }
  }
  if (json_stdout && (o.output == "-" || o.report == "-"))
    throw CLI::ValidationError(o.json ? "--json" : "--summary",
                               "the JSON summary on the standard output needs -o FILE (or no -o) and no --report -: "
                               "stdout is taken");
  if (o.format == "segments" && !setpoints)
    throw CLI::ValidationError("--format", "--format segments needs -o FILE (or -o -): the stream is the output");
  Machine machine = o.machine.empty() ? default_machine() : read_machine(o.machine);
  if (o.machine.empty()) validate(machine);
  InterruptGuard interrupt;
  Progress progress(!o.quiet);
  const long total_lines = progress.enabled() ? count_lines(o.program) : 0;
  const SetpointFormat format = o.format == "binary" ? SetpointFormat::binary : SetpointFormat::csv;
  const bool segments = o.format == "segments";
  PipelineOptions options;
  options.blend = !o.no_blend;
  options.smooth = !o.no_smooth;
  // The summary says which dialect was taken and why.
  options.reader = reader_options(o.read, o.program, &machine, true);
  options.time_optimal = o.time_optimal;
  options.derivatives = segments;  // the stream fits the exact velocity and acceleration
  Pipeline pipeline(std::move(machine), options);
  std::unique_ptr<RunReportBuilder> builder;
  if (!o.report.empty()) builder = std::make_unique<RunReportBuilder>(pipeline.machine(), pipeline.moves(), pipeline.layout());
  RunResult result;
  const AxisLayout layout = pipeline.prepare(o.program);
  segments::SegmentStats stream;
  PipelineEvents events;
  if (builder) events.observer = [&](const verify::SampleMeasure& m) { builder->observe(m); };
  events.progress = [&](long line) {
    InterruptGuard::check();
    if (total_lines > 0)
      progress.update("running", static_cast<double>(line) / static_cast<double>(total_lines),
                      fmt::format("line {} of {}", line, total_lines));
  };
  auto produce = [&](std::ostream& out) {
    std::optional<SetpointWriter> writer;
    std::optional<segments::SegmentWriter> stream_writer;
    if (segments) {
      segments::SegmentOptions so;
      so.tolerance_mm = o.segment_tolerance_mm;
      so.bounds = segments::axis_bounds(pipeline.machine(), layout);
      stream_writer.emplace(out, pipeline.machine().servo_period_s, layout, so);
    } else {
      writer.emplace(out, format, pipeline.machine().servo_period_s, layout);
    }
    events.setpoint = [&](const trajectory::Setpoint& sp) {
      InterruptGuard::check();
      if (writer) {
        writer->write(sp);
      } else {
        stream_writer->write(sp);
      }
    };
    result = pipeline.run(o.program, events);
    if (stream_writer) {
      stream_writer->finish();
      stream = stream_writer->stats();
    }
    InterruptGuard::check();  // (a signal during the last blocks: the file is not renamed into place)
  };
  // The files this run writes, for the message of an interrupted run.
  std::vector<std::string> outputs;
  for (const std::string& f : {o.output, o.report, o.summary})
    if (!f.empty() && f != "-") outputs.push_back(f);
  try {
    if (!setpoints) {
      events.setpoint = [&](const trajectory::Setpoint&) { InterruptGuard::check(); };
      result = pipeline.run(o.program, events);
    } else if (o.output == "-") {
      produce(std::cout);
    } else {
      write_file_atomically(o.output, produce, inputs);
    }
    progress.clear();
    InterruptGuard::check();
    if (builder) {
      const report::Report rep = builder->build(result.check, result.total_time_s, o.program);
      std::vector<std::filesystem::path> report_inputs = inputs;
      if (setpoints && o.output != "-") report_inputs.emplace_back(o.output);
      report::write_html_report(rep, o.report, report_inputs, RunReportBuilder::render_options());
    }
  } catch (Interrupted& e) {
    progress.clear();
    e.not_written = outputs;
    throw;
  }
  if (segments && !result.summary_json.empty()) {
    // What the stream holds, beside the check of the planner's setpoints it was fitted to.
    nlohmann::ordered_json summary = nlohmann::ordered_json::parse(result.summary_json);
    const double motion_s = std::max(result.total_time_s, pipeline.machine().servo_period_s);
    summary["segments"] = {
        {"pieces", stream.pieces},
        {"anchors", stream.anchors},
        {"float32_pieces", stream.float32_pieces},
        {"pieces_by_degree", stream.by_degree},
        {"limit_fallbacks", stream.limit_fallbacks},
        {"bytes", stream.bytes},
        {"bytes_per_second", static_cast<double>(stream.bytes) / motion_s},
        {"setpoints_per_piece", stream.pieces > 0 ? static_cast<double>(stream.setpoints) / static_cast<double>(stream.pieces) : 0.0},
        {"size_ratio_to_binary",
         static_cast<double>(binary_setpoint_bytes(layout, static_cast<std::uint64_t>(stream.setpoints))) /
             static_cast<double>(std::max<std::uint64_t>(stream.bytes, 1))},
        {"tolerance_mm", o.segment_tolerance_mm},
        {"max_error_mm", stream.max_error_mm},
        {"max_speed_error_mm_s", stream.max_speed_error_mm_s}};
    result.summary_json = summary.dump(2) + "\n";
  }
  // For a person: what was written where (write_summaries adds the summary file).
  std::string footer;
  if (!setpoints) {
    footer = "setpoints not written: -o FILE writes them (CSV; --format binary, segments), -o - to stdout";
    if (!json_stdout) footer += "; --json prints this summary as JSON";
  } else if (o.output != "-") {
    footer = fmt::format("setpoints {} ({})", o.output, o.format);
  }
  if (!o.report.empty() && o.report != "-")
    footer += fmt::format("{}report    {} (open it in a browser)", footer.empty() ? "" : "\n", o.report);
  write_summaries(summaries, result.summary_json, inputs, o.program, pipeline.machine(), options.reader, result,
                  pipeline.moves(), footer);
  return result.passed;
}

}  // namespace

void register_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run",
                                     "Run a part program: plan the motion on the machine and write the "
                                     "setpoints at its servo period, with an independent check of the limits.");
  cmd->add_option("PROGRAM", o->program, "part program (G-code)")->required();
  cmd->add_option("--machine", o->machine, "machine file: Kontur TOML, or LinuxCNC INI (default: embedded)");
  cmd->add_option("-o,--output", o->output,
                  "setpoint file, '-' for stdout (none: no setpoints are written, only the summary is printed)");
  cmd->add_option("--format", o->format,
                  "csv or binary setpoints (docs/setpoints.md), or segments: the stream of polynomial pieces the "
                  "lower level replays (docs/segments.md, kontur replay)")
      ->check(CLI::IsMember({"csv", "binary", "segments"}))
      ->capture_default_str();
  cmd->add_option("--segment-tolerance", o->segment_tolerance_mm,
                  "with --format segments: largest distance of a replayed setpoint from the planner's [mm] ([deg] "
                  "for A B C; the path speed gets it divided by the servo period [mm/s])")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--summary", o->summary,
                  "JSON summary file, per program and per block (docs/setpoints.md); - for stdout (as --json)");
  cmd->add_flag("--json", o->json, "print the JSON summary on stdout instead of the short one (not with -o -)");
  cmd->add_option("--report", o->report,
                  "write a self-contained HTML report (path coloured by speed, speed against feed, axis velocity, "
                  "acceleration and jerk with their limits, chord error, per-block table; docs/report.md) to FILE, "
                  "atomically; - for stdout (not with -o -)")
      ->type_name("FILE");
  cmd->add_flag("--time-optimal", o->time_optimal,
                "add the time-optimal reference (acceleration-limited) and the ratio of the total time to it");
  cmd->add_flag("--quiet", o->quiet, "no progress bar and no short summary (errors are still printed)");
  cmd->add_flag("--no-blend", o->no_blend,
                "do not blend corners between lines and arcs within the G64 tolerance (each corner is a junction)");
  cmd->add_flag("--no-smooth", o->no_smooth,
                "do not smooth runs of dense lines within the G64 tolerance (each line runs as programmed)");
  add_program_read_options(cmd, o->read);
  cmd->footer(
      "Example:\n  kontur run examples/programs/square_arc.ngc   (the short summary: time, limits, PASS/FAIL)\n"
      "  kontur run examples/programs/square_arc.ngc -o square_arc.csv --summary square_arc.json "
      "--report square_arc.html\n"
      "  kontur run examples/programs/square_arc.ngc -o - --quiet | head   (setpoints to stdout)\n"
      "  kontur run examples/programs/square_arc.ngc --json   (the JSON summary on stdout)\n"
      "Without -o no setpoints are written. The short summary goes to stdout, or to stderr when stdout carries "
      "the setpoints or the JSON; PASS and FAIL are coloured on a terminal unless NO_COLOR is set. A progress bar "
      "is drawn on stderr when it is a terminal and the run takes longer than a second.\n"
      "Exit codes: 0 within the limits, 1 invalid program or machine, 2 wrong command line, 4 the check found a "
      "limit exceeded (see the summary), 130 / 143 stopped by SIGINT / SIGTERM (nothing written, earlier files "
      "as they were).");
  cmd->callback([o, &exit_code]() { exit_code = run_program(*o) ? exit_ok : exit_check_failed; });
}

}  // namespace kontur::app
