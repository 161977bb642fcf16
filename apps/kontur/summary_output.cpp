#include "summary_output.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <kontur/io/atomic_file.hpp>

namespace kontur::app {

namespace {

// "5.270 s", or with hours and minutes for long jobs: "17334.303 s (4 h 48 min 54 s)".
std::string duration_text(double s) {
  std::string t = fmt::format("{:.3f} s", s);
  if (s >= 60.0) {
    const long whole = std::lround(std::floor(s));
    const long h = whole / 3600, m = whole / 60 % 60, sec = whole % 60;
    t += h > 0 ? fmt::format(" ({} h {} min {} s)", h, m, sec) : fmt::format(" ({} min {} s)", m, sec);
  }
  return t;
}

// A length [mm] with 3 decimals, or in scientific notation when below 0.001 mm (never "-0").
std::string mm(double v) {
  if (v == 0.0) return "0 mm";
  return std::abs(v) >= 1e-3 ? fmt::format("{:.3f} mm", v) : fmt::format("{:.1e} mm", v);
}

bool colour_for(std::FILE* out) {
  const char* no_colour = std::getenv("NO_COLOR");
  return isatty(fileno(out)) != 0 && (no_colour == nullptr || *no_colour == '\0');
}

// The short summary for a person (write_summaries).
void print_human_summary(std::FILE* out, const std::string& program, const Machine& machine,
                         const gcode::ReaderOptions& reading, const RunResult& result,
                         const std::vector<program::Move>& moves, const std::string& footer) {
  const verify::Report& r = result.check;
  double feed_mm = 0.0, rapid_mm = 0.0;
  long rapids = 0;
  for (const program::Move& m : moves) {
    if (std::strcmp(m.type, "rapid") == 0) {
      rapid_mm += m.length_mm;
      ++rapids;
    } else {
      feed_mm += m.length_mm;
    }
  }
  std::string letters;
  for (const AxisLimits& a : machine.axes) letters += a.name;
  fmt::print(out, "program   {}{}\n", program,
             reading.dialect ? fmt::format(" ({}: {})", gcode::to_string(*reading.dialect), reading.dialect_reason)
                             : std::string());
  fmt::print(out, "machine   {}: {}, servo period {:g} ms\n", machine.source, letters, machine.servo_period_s * 1e3);
  fmt::print(out, "moves     {} ({} rapid), path {} (feed {}, rapid {})\n", moves.size(), rapids,
             mm(feed_mm + rapid_mm), mm(feed_mm), mm(rapid_mm));
  fmt::print(out, "time      {}, {} setpoints\n", duration_text(result.total_time_s), result.setpoints);
  fmt::print(out, "limits    largest velocity {:.3f}, acceleration {:.3f}, jerk {:.3f} of the limits\n",
             r.max_velocity_ratio, r.max_acceleration_ratio, r.max_jerk_ratio);
  fmt::print(out, "path      error {}, chord error {} (tolerance {}), end {}\n", mm(r.max_path_error_mm),
             mm(r.max_chord_error_mm), mm(machine.chord_tolerance_mm), mm(r.end_error_mm));
  if (r.blends > 0)
    fmt::print(out, "blends    {} corners, largest deviation {} (tolerance {})\n", r.blends,
               mm(r.max_blend_deviation_mm), mm(r.blend_tolerance_mm));
  if (r.smoothed_lines > 0)
    fmt::print(out, "smoothed  {} lines, largest deviation {} (tolerance {})\n", r.smoothed_lines,
               mm(r.max_smoothing_deviation_mm), mm(r.smoothing_tolerance_mm));
  const bool colour = colour_for(out);
  const bool passed = r.passed(machine);
  const char* on = colour ? (passed ? "\033[1;32m" : "\033[1;31m") : "";
  const char* off = colour ? "\033[0m" : "";
  if (passed) {
    fmt::print(out, "{}PASS{}      every limit held\n", on, off);
  } else {
    fmt::print(out, "{}FAIL{}\n", on, off);
    for (const std::string& f : r.failures(machine)) fmt::print(out, "          {}\n", f);
  }
  if (!footer.empty()) fmt::print(out, "{}\n", footer);
  std::fflush(out);
}

}  // namespace

void write_summaries(const SummaryOutputs& to, const std::string& json, const std::vector<std::filesystem::path>& inputs,
                     const std::string& program, const Machine& machine, const gcode::ReaderOptions& reading,
                     const RunResult& result, const std::vector<program::Move>& moves, std::string footer) {
  const bool json_stdout = to.json_on_stdout();
  const bool file = !to.file.empty() && to.file != "-";
  if (file) write_file_atomically(to.file, [&](std::ostream& out) { out << json; }, inputs);
  if (json_stdout) std::cout << json << std::flush;
  if (to.quiet) return;
  if (file) footer += fmt::format("{}summary   {}", footer.empty() ? "" : "\n", to.file);
  print_human_summary(to.stdout_taken || json_stdout ? stderr : stdout, program, machine, reading, result, moves,
                      footer);
}

}  // namespace kontur::app
