// `kontur compress PROGRAM -o OUT --tolerance MM`: the program with its G1 runs fitted by fewer
// blocks (compress/compressor.hpp), a summary for a person, a JSON report per run.
#include "commands.hpp"
#include "program_options.hpp"

#include <kontur/compress/compressor.hpp>
#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <memory>
#include <sstream>

namespace kontur::app {
namespace {

struct CompressCommandOptions {
  std::string program, output, report, curves;
  double tolerance_mm = 0.01;
  bool quiet = false;
  ProgramReadOptions read;
};

// --curves: "lines" (none but lines) or a comma list of arcs, arcs3d, conics, splines.
compress::CurveKinds parse_curves(const std::string& list) {
  compress::CurveKinds k{false, false, false, false};
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item == "arcs")
      k.arcs = true;
    else if (item == "arcs3d")
      k.arcs_3d = true;
    else if (item == "conics")
      k.conics = true;
    else if (item == "splines")
      k.splines = true;
    else if (item != "lines")
      throw CLI::ValidationError("--curves", "unknown curve '" + item + "' (lines, arcs, arcs3d, conics, splines)");
  }
  return k;
}

std::string curves_text(const compress::CurveKinds& k) {
  std::string s = "lines";
  if (k.arcs) s += ", arcs";
  if (k.arcs_3d) s += ", 3-D arcs";
  if (k.conics) s += ", conics";
  if (k.splines) s += ", splines";
  return s;
}

nlohmann::ordered_json report_json(const CompressCommandOptions& o, const compress::CompressOptions& c,
                                   const compress::CompressResult& r) {
  nlohmann::ordered_json j;
  j["program"] = o.program;
  j["output"] = o.output;
  j["dialect"] = gcode::to_string(r.dialect.dialect);
  j["tolerance_mm"] = c.tolerance_mm;
  j["curves"] = {{"arcs", c.kinds.arcs}, {"arcs3d", c.kinds.arcs_3d}, {"conics", c.kinds.conics},
                 {"splines", c.kinds.splines}};
  j["feed_blocks_in"] = r.feed_blocks_in;
  j["feed_blocks_out"] = r.feed_blocks_out;
  j["ratio"] = r.feed_blocks_out > 0 ? static_cast<double>(r.feed_blocks_in) / static_cast<double>(r.feed_blocks_out)
                                     : 0.0;
  j["max_deviation_mm"] = r.max_deviation_mm;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const compress::RunReport& run : r.runs) {
    nlohmann::ordered_json x;
    x["lines"] = {run.first_line, run.last_line};
    x["output_line"] = run.output_line;
    x["blocks_in"] = run.lines_in;
    x["blocks_out"] = run.blocks_out;
    nlohmann::ordered_json pieces = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < run.pieces.size(); ++k)
      if (run.pieces[k] > 0) pieces[compress::to_string(static_cast<compress::PieceKind>(k))] = run.pieces[k];
    x["pieces"] = pieces;
    x["deviation_mm"] = run.deviation_mm;
    if (!run.kept.empty()) x["kept"] = run.kept;
    runs.push_back(x);
  }
  j["runs"] = runs;
  return j;
}

void run_compress(const CompressCommandOptions& o) {
  check_output_not_input(o.output, {o.program});
  if (!o.report.empty()) check_output_not_input(o.report, {o.program, o.output});
  compress::CompressOptions c;
  c.tolerance_mm = o.tolerance_mm;
  c.reader = reader_options(o.read, o.program, nullptr, true);
  c.kinds = o.curves.empty() ? compress::default_kinds(c.reader.dialect.value_or(gcode::Dialect::linuxcnc))
                             : parse_curves(o.curves);
  const auto t0 = std::chrono::steady_clock::now();
  const compress::CompressResult r = compress::compress_program(o.program, c);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_file_atomically(o.output, [&](std::ostream& out) { out << r.text; }, {o.program});
  if (!o.report.empty())
    write_file_atomically(o.report, [&](std::ostream& out) { out << report_json(o, c, r).dump(2) << '\n'; },
                          {o.program, o.output});
  if (o.quiet) return;
  std::size_t compressed = 0, kept = 0;
  std::array<std::size_t, 5> pieces{};
  for (const compress::RunReport& run : r.runs) {
    if (run.kept.empty()) {
      ++compressed;
      for (std::size_t k = 0; k < pieces.size(); ++k) pieces[k] += run.pieces[k];
    } else {
      ++kept;
    }
  }
  fmt::print("{} -> {} ({}, tolerance {} mm, curves: {})\n", o.program, o.output, gcode::to_string(r.dialect.dialect),
             o.tolerance_mm, curves_text(c.kinds));
  fmt::print("feed blocks     {} -> {} ({:.2f} times fewer)\n", r.feed_blocks_in, r.feed_blocks_out,
             r.feed_blocks_out > 0 ? static_cast<double>(r.feed_blocks_in) / static_cast<double>(r.feed_blocks_out)
                                   : 0.0);
  fmt::print("runs of G1      {} compressed, {} kept as programmed\n", compressed, kept);
  std::string made;
  for (std::size_t k = 0; k < pieces.size(); ++k)
    if (pieces[k] > 0)
      made += fmt::format("{}{} {}", made.empty() ? "" : ", ", pieces[k], compress::to_string(static_cast<compress::PieceKind>(k)));
  fmt::print("written as      {}\n", made.empty() ? "nothing" : made);
  fmt::print("deviation       {:.6f} mm at most, both ways (the written program read again)\n", r.max_deviation_mm);
  fmt::print("time            {:.3f} s ({:.0f} input blocks/s)\n", seconds,
             seconds > 0.0 ? static_cast<double>(r.input_blocks) / seconds : 0.0);
}

}  // namespace

void register_compress_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<CompressCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compress",
      "Write the program with its runs of G1 lines replaced by fewer blocks (lines, G2/G3 arcs, 3-D arcs, conics, "
      "splines) within a tolerance of the programmed lines, both ways; everything else is copied as it is.");
  cmd->add_option("PROGRAM", opts->program, "part program")->required();
  cmd->add_option("-o,--output", opts->output, "the compressed program (never the input)")->required();
  cmd->add_option("--tolerance", opts->tolerance_mm,
                  "largest distance of the new path from the programmed lines and of every programmed point from "
                  "the new path [mm] (default 0.01)");
  cmd->add_option("--curves", opts->curves,
                  "curves to write, a comma list of arcs, arcs3d, conics, splines (or 'lines'); default: those the "
                  "dialect's control reads (LinuxCNC arcs, splines G6.2; Fanuc/Mitsubishi arcs, G02.4, G06.2; "
                  "Sinumerik arcs, CIP; Haas, grbl, Mach3 arcs). conics: Kontur's CONIC block, read by Kontur only");
  cmd->add_option("--report", opts->report, "JSON report: per run its lines, what it became, its deviation");
  cmd->add_flag("--quiet", opts->quiet, "print nothing on success");
  add_program_read_options(cmd, opts->read);
  cmd->footer(
      "The output is read again and checked: every new piece (sampled) within the tolerance of its\n"
      "programmed lines and every programmed point within the tolerance of the new piece; a piece that is\n"
      "not is written as its lines. docs/compress.md has the rules.\n"
      "Example:\n  kontur compress ../shared/data/gcode/3D_Chips.ngc -o chips_compressed.ngc --tolerance 0.01\n"
      "Exit codes: 0 written, 1 invalid program, value or file, 2 wrong command line, 3 internal error.");
  cmd->callback([opts, &exit_code]() {
    run_compress(*opts);
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
