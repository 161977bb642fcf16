// The JSON result of checking a part program (report/program_check.hpp).
#include <fmt/format.h>

#include <kontur/axes.hpp>
#include <kontur/report/program_check.hpp>
#include <nlohmann/json.hpp>
#include <functional>
#include <optional>
#include <string>

namespace kontur::report {

std::string program_check_json(const std::string& program, const gcode::ReaderOptions& options, bool with_blocks) {
  // One pass: a program with an error throws before the document is returned, so it yields
  // nothing but the error.
  nlohmann::ordered_json j;
  j["file"] = program;
  j["valid"] = true;
  j["dialect"] = nullptr;  // (set after the pass; its place in the document is here)
  auto& blocks = j["blocks"] = nlohmann::ordered_json::array();
  std::function<void(const gcode::Block&, std::optional<double>)> on_block;
  if (with_blocks)
    on_block = [&](const gcode::Block& b, std::optional<double> len) {
      nlohmann::ordered_json e;
      e["line"] = b.location.line;
      e["column"] = b.location.column;
      if (b.location.n_number >= 0) e["n"] = b.location.n_number;
      e["type"] = gcode::to_string(b.type);
      if (len) e["length_mm"] = *len;
      else e["length_mm"] = nullptr;
      e["feed"] = b.type == gcode::BlockType::rapid || b.type == gcode::BlockType::dwell ? 0.0 : b.feed.value;
      e["feed_mode"] = b.feed.mode == gcode::FeedMode::inverse_time ? "inverse_time" : "mm_per_min";
      if (b.type == gcode::BlockType::dwell) e["dwell_s"] = b.dwell_s;
      if (b.canned_cycle) e["canned_cycle"] = fmt::format("G{}", b.canned_cycle);
      e["end"] = {b.end.x(), b.end.y(), b.end.z()};
      if (b.moves_extra_axes()) {  // only the extra axes that move: A B C [deg], U V W [mm]
        nlohmann::ordered_json es = nlohmann::ordered_json::object(), ee = nlohmann::ordered_json::object();
        for (std::size_t i = 0; i < b.extra_start.size(); ++i)
          if (b.extra_start[i] != b.extra_end[i]) {
            const std::string letter(1, extra_axis_letters[i]);
            es[letter] = b.extra_start[i];
            ee[letter] = b.extra_end[i];
          }
        e["extra_start"] = std::move(es);  // (a reference into e would not survive the next insertion)
        e["extra_end"] = std::move(ee);
      }
      blocks.push_back(e);
    };
  const gcode::ProgramSummary s = gcode::check_program(program, options, on_block);
  j["dialect"] = {{"name", gcode::to_string(s.dialect.dialect)}, {"reason", s.dialect.reason}};
  auto& t = j["totals"];
  t["lines"] = s.lines;
  t["blocks"] = s.blocks;
  for (int i = 0; i < gcode::block_type_count; ++i)
    t["by_type"][gcode::to_string(static_cast<gcode::BlockType>(i))] = s.by_type[static_cast<std::size_t>(i)];
  t["path_length_mm"] = s.path_length_mm;
  t["rapid_length_mm"] = s.rapid_length_mm;
  t["dwell_s"] = s.dwell_s;
  t["blocks_without_length"] = s.blocks_without_length;
  t["warnings"] = s.warnings;
  t["warning_count"] = s.warning_count;
  return j.dump(2);
}

}  // namespace kontur::report
