#include <kontur/report/summary.hpp>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>

namespace kontur::report {
namespace {
// Stands for the per-move array while the rest of the summary is written (no key or value of the
// summary can contain it).
constexpr const char* blocks_placeholder = "\x01kontur-summary-blocks\x01";
}  // namespace

std::string summary_json(const std::string& program, const Machine& machine, const verify::Report& r,
                         const std::vector<program::Move>& moves, double total_time_s, const SummaryExtras& extras) {
  nlohmann::ordered_json j;
  j["program"] = program;
  j["machine"] = machine.source;
  if (extras.dialect) j["dialect"] = {{"name", gcode::to_string(extras.dialect->dialect)}, {"reason", extras.dialect->reason}};
  j["servo_period_s"] = machine.servo_period_s;
  j["setpoints"] = r.samples;
  j["total_time_s"] = total_time_s;
  j["moves"] = moves.size();
  j["max_velocity_ratio"] = r.max_velocity_ratio;
  j["max_acceleration_ratio"] = r.max_acceleration_ratio;
  j["max_jerk_ratio"] = r.max_jerk_ratio;
  j["max_path_error_mm"] = r.max_path_error_mm;
  j["max_chord_error_mm"] = r.max_chord_error_mm;
  j["chord_tolerance_mm"] = machine.chord_tolerance_mm;
  j["end_error_mm"] = r.end_error_mm;
  if (r.worst_extra_axis != ' ' || r.max_extra_axis_error > 0.0) {  // only where an extra axis is in the layout
    j["max_extra_axis_error"] = r.max_extra_axis_error;
    j["worst_extra_axis"] = std::string(1, r.worst_extra_axis);
  }
  j["blends"] = r.blends;
  j["max_blend_deviation_mm"] = r.max_blend_deviation_mm;
  j["blend_tolerance_mm"] = r.blend_tolerance_mm;
  j["smoothed_lines"] = r.smoothed_lines;
  j["max_smoothing_deviation_mm"] = r.max_smoothing_deviation_mm;
  j["smoothing_tolerance_mm"] = r.smoothing_tolerance_mm;
  j["passed"] = r.passed(machine);
  j["failures"] = r.failures(machine);
  // Per move (docs/setpoints.md), written entry by entry into the text below: a tree of every
  // move's entry would cost more than the rest of a long job's memory.
  j["blocks"] = blocks_placeholder;
  if (extras.time_optimal_s) {
    j["time_optimal_s"] = *extras.time_optimal_s;
    // No motion: both times are 0, the ratio 1 (never NaN in the output).
    j["time_ratio"] = *extras.time_optimal_s > 0.0 ? total_time_s / *extras.time_optimal_s : 1.0;
  }
  if (extras.setpoint_file) j["setpoint_file"] = *extras.setpoint_file;
  const std::string head_and_tail = j.dump(2) + "\n";
  const std::string marker = nlohmann::ordered_json(blocks_placeholder).dump();
  const std::size_t at = head_and_tail.find(marker);
  std::string text = head_and_tail.substr(0, at) + "[";
  const std::size_t n = std::min(r.blocks.size(), moves.size());
  text.reserve(head_and_tail.size() + 480 * n);  // an entry is about 400-470 characters
  // Each entry as dump(2) writes an object two levels down (every line indented by 4 more spaces),
  // its values formatted by the same serializer, without building the object.
  const auto field = [&text](const char* key, const nlohmann::ordered_json& value, bool last = false) {
    text += "      \"";
    text += key;
    text += "\": ";
    text += value.dump();
    text += last ? "\n" : ",\n";
  };
  for (std::size_t i = 0; i < n; ++i) {
    const verify::BlockStats& b = r.blocks[i];
    text += i == 0 ? "\n    {\n" : ",\n    {\n";
    field("line", b.source_line);
    field("type", moves[i].type);
    field("length_mm", moves[i].length_mm);
    field("feed_mm_s", moves[i].feed_mm_s);
    field("setpoints", b.samples);
    field("t_start_s", b.samples > 0 ? nlohmann::ordered_json(b.t_first_s) : nlohmann::ordered_json(nullptr));
    field("t_end_s", b.samples > 0 ? nlohmann::ordered_json(b.t_last_s) : nlohmann::ordered_json(nullptr));
    field("max_velocity_ratio", b.max_velocity_ratio);
    field("max_acceleration_ratio", b.max_acceleration_ratio);
    field("max_jerk_ratio", b.max_jerk_ratio);
    field("max_path_error_mm", b.max_path_error_mm);
    const bool reference = i < extras.move_time_optimal_s.size();
    field("max_chord_error_mm", b.max_chord_error_mm, !reference);
    // the reference's time on this move, against the planner's (about setpoints x servo period)
    if (reference) field("time_optimal_s", extras.move_time_optimal_s[i], true);
    text += "    }";
  }
  text += n > 0 ? "\n  ]" : "]";
  text.append(head_and_tail, at + marker.size());
  return text;
}

}  // namespace kontur::report
