// `kontur replay STREAM`: the lower level on the host. Runs the freestanding C library a
// controller would run (lower_level/kontur_ll.c) over a segment stream of `kontur run --format
// segments` (docs/segments.md) and writes its setpoints in the CSV or binary format of `kontur run`
// (the same rows: t, the axes, v, block), which `kontur verify` then checks like any others.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/io/setpoint_writer.hpp>
#include <kontur/segments/segment_stream.hpp>
#include <memory>
#include <optional>

#include "commands.hpp"

namespace kontur::app {
namespace {

struct ReplayOptions {
  std::string stream;
  std::string output = "-";
  std::string format = "csv";
  bool quiet = false;
};

void replay(const ReplayOptions& o) {
  std::ifstream in(o.stream, std::ios::binary);
  if (!in)
    throw InputError("file-open", fmt::format("{}: cannot open the segment stream: {}", o.stream,
                                              std::error_code(errno, std::generic_category()).message()));
  const SetpointFormat format = o.format == "binary" ? SetpointFormat::binary : SetpointFormat::csv;
  segments::SegmentStats stats;
  segments::SegmentHeader header;
  auto produce = [&](std::ostream& out) {
    std::optional<SetpointWriter> writer;
    stats = segments::replay_segments(
        in, o.stream,
        [&](const segments::SegmentHeader& h) {
          header = h;
          writer.emplace(out, format, h.period_s, h.layout);
        },
        [&](const trajectory::Setpoint& sp) { writer->write(sp); });
  };
  if (o.output == "-") {
    produce(std::cout);
  } else {
    write_file_atomically(o.output, produce, {o.stream});
  }
  if (!o.quiet)
    std::fprintf(stderr,
                 "kontur replay: %ld setpoints from %ld pieces (%ld anchors), %llu bytes, axes %s, period %g s, "
                 "tolerance %g mm\n",
                 stats.setpoints, stats.pieces, stats.anchors, static_cast<unsigned long long>(stats.bytes),
                 header.layout.letters().c_str(), header.period_s, header.tolerance_mm);
}

}  // namespace

void register_replay_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App* cmd = app.add_subcommand(
      "replay",
      "Run the lower level (lower_level/, freestanding C99: forward differences, one setpoint per call) on a "
      "segment stream of `kontur run --format segments` and write its setpoints as `kontur run` does.");
  cmd->add_option("STREAM", o->stream, "segment stream (docs/segments.md)")->required();
  cmd->add_option("-o,--output", o->output, "setpoint file, '-' for stdout")->capture_default_str();
  cmd->add_option("--format", o->format, "csv or binary (docs/setpoints.md)")
      ->check(CLI::IsMember({"csv", "binary"}))
      ->capture_default_str();
  cmd->add_flag("--quiet", o->quiet, "no line of totals on stderr (errors are still printed)");
  cmd->footer(
      "Example:\n  kontur run examples/programs/square_arc.ngc --format segments -o square_arc.seg --quiet\n"
      "  kontur replay square_arc.seg -o square_arc_replayed.csv\n"
      "  kontur verify examples/programs/square_arc.ngc square_arc_replayed.csv\n"
      "A damaged stream (a CRC-32 that does not match, a piece lost or out of order) is refused with the index "
      "and byte offset of the piece; no output file is left.\n"
      "Exit codes: 0 replayed, 1 missing or damaged stream, 2 wrong command line.");
  cmd->callback([o, &exit_code]() {
    replay(*o);
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
