// `kontur check PROGRAM`: reads a G-code part program, validates every block and prints per
// block its line, type, length and feed, then the totals; --json for tools.
#include "commands.hpp"
#include "program_options.hpp"

#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/report/program_check.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace kontur::app {
namespace {

struct CheckOptions {
  std::string file;
  bool json = false;
  bool quiet = false;
  ProgramReadOptions read;
};

std::string num(double v) {
  if (v == 0.0) v = 0.0;
  return fmt::format("{:.6f}", v);
}

std::string feed_text(const gcode::Block& b) {
  if (b.type == gcode::BlockType::rapid) return "rapid";
  if (b.type == gcode::BlockType::dwell) return fmt::format("dwell {} s", b.dwell_s);
  if (b.feed.mode == gcode::FeedMode::inverse_time) return fmt::format("F{} 1/min ({} s)", b.feed.value, b.feed.duration_s());
  return fmt::format("{} mm/min", b.feed.value);
}

// The extra axes a block moves, as " [A 0.000000 -> 90.000000 deg, W ...]" (empty when none moves: X Y Z
// programs print as before).
std::string extra_text(const gcode::Block& b) {
  std::string s;
  for (std::size_t i = 0; i < b.extra_start.size(); ++i) {
    if (b.extra_start[i] == b.extra_end[i]) continue;
    s += s.empty() ? " [" : ", ";
    s += fmt::format("{} {} -> {} {}", extra_axis_letters[i], num(b.extra_start[i]), num(b.extra_end[i]),
                     i < 3 ? "deg" : "mm");
  }
  if (!s.empty()) s += "]";
  return s;
}

void run_check(const CheckOptions& o) {
  // The dialect line goes to stderr, except in JSON (it is a field there).
  const gcode::ReaderOptions ro = reader_options(o.read, o.file, nullptr, o.json);
  // Validate first: a program with an error prints nothing but the error (and exits 1).
  if (o.json) {
    fmt::print("{}\n", report::program_check_json(o.file, ro, !o.quiet));
    return;
  }
  const gcode::ProgramSummary s = gcode::check_program(o.file, ro);
  for (const auto& w : s.warnings) std::fprintf(stderr, "kontur: %s\n", w.c_str());
  if (!o.quiet) {
    fmt::print("{:>8} {:>7} {:<10} {:>16} {}\n", "line", "N", "type", "length [mm]", "feed");
    gcode::check_program(o.file, ro, [](const gcode::Block& b, std::optional<double> len) {
      fmt::print("{:>8} {:>7} {:<10} {:>16} {}{}{}\n", b.location.line,
                 b.location.n_number >= 0 ? fmt::format("N{}", b.location.n_number) : std::string(),
                 gcode::to_string(b.type), len ? num(*len) : std::string("n/a"), feed_text(b),
                 b.canned_cycle ? fmt::format(" (G{})", b.canned_cycle) : std::string(), extra_text(b));
    });
  }
  fmt::print("\nprogram     {}: valid, {} lines, {} blocks\n", o.file, s.lines, s.blocks);
  fmt::print("blocks      ");
  bool first = true;
  for (int i = 0; i < gcode::block_type_count; ++i)
    if (s.by_type[static_cast<std::size_t>(i)] > 0) {
      fmt::print("{}{} {}", first ? "" : ", ", s.by_type[static_cast<std::size_t>(i)],
                 gcode::to_string(static_cast<gcode::BlockType>(i)));
      first = false;
    }
  fmt::print("{}\n", first ? "none" : "");
  fmt::print("path length {} mm (feed moves{})\n", num(s.path_length_mm),
             s.blocks_without_length ? fmt::format("; {} blocks without a length not counted", s.blocks_without_length)
                                     : std::string());
  fmt::print("rapid       {} mm\n", num(s.rapid_length_mm));
  if (s.dwell_s > 0.0) fmt::print("dwell       {} s\n", s.dwell_s);
  if (s.warning_count) fmt::print("warnings    {}\n", s.warning_count);
}

}  // namespace

void register_check_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Validate a G-code part program and print per block its line, type, length and feed, then totals "
               "(blocks by type, path length, rapid length). Lengths in mm, feeds in mm/min (G93: 1/min).");
  cmd->add_option("PROGRAM", opts->file, "part program (RS274/ISO 6983 with LinuxCNC, Fanuc and Sinumerik extensions)")
      ->required();
  cmd->add_flag("--json", opts->json, "print the result as JSON");
  cmd->add_flag("--quiet", opts->quiet, "print only the totals");
  add_program_read_options(cmd, opts->read);
  cmd->footer(
      "Kontur's conic block (no control has one; the name collides with no code of Fanuc, Mitsubishi,\n"
      "LinuxCNC or Sinumerik):\n"
      "  CONIC X- Y- Z- I1=- J1=- K1=- I2=- J2=- K2=- I3=- J3=- K3=- [F-]\n"
      "  the conic from the current position through the three intermediate points (I1 J1 K1), (I2 J2 K2),\n"
      "  (I3 J3 K3), in this order, to the end point X Y Z; all nine intermediate words are required;\n"
      "  G91 makes them relative to the start point. The five points must be distinct, no three collinear,\n"
      "  all in one plane (within 0.001 mm) and in order along one arc of the conic; in messages they are\n"
      "  r1 (start), r2, r3, r4 (I1.., I2.., I3..) and r5 (end).\n"
      "3-D circle through an intermediate point: CIP X- Y- Z- I1=- J1=- K1=- (Sinumerik) or\n"
      "  G02.4 X- Y- Z- (intermediate point) followed by X- Y- Z- (end point) (Fanuc).\n"
      "See docs/gcode.md for the whole syntax, the errors and the unsupported features.\n"
      "Example:\n  kontur check ../shared/data/gcode/3D_Chips.ngc --quiet\n"
      "Exit codes: 0 valid program, 1 invalid program or file (file:line:column: word: rule), 2 wrong command line.");
  cmd->callback([opts, &exit_code]() {
    run_check(*opts);
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
