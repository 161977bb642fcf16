#include <kontur/gcode/reader.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/plan/program_moves.hpp>
#include <kontur/plan/program_path.hpp>

namespace kontur::plan {

ProgramPath::ProgramPath(const Machine& machine, bool blend) : machine_(machine), blender_(blend, &machine) {}

void ProgramPath::take(std::vector<BlendedMove>& ready, const ProgramEvents& events) {
  for (const BlendedMove& bm : ready) {
    const Curve* curve = bm.move.curve.get();
    const BlockInfo& info = blocks_[bm.tag];
    const verify::ProgrammedCorner* corner = nullptr;
    if (bm.blend) corner = &corners_.emplace_back(verify::ProgrammedCorner{bm.before, bm.corner, bm.after, bm.tolerance_mm});
    // A move the blender did not trim keeps its block's curve and length.
    entries_.push_back({bm.move, bm.blend ? "blend" : info.type, curve == info.curve ? info.length_mm : length(*curve)});
    check_moves_.push_back({curve, bm.move.source_line, corner});
    if (events.move) events.move(bm.move);
  }
  ready.clear();
}

void ProgramPath::read(const std::string& program, const ProgramEvents& events) {
  std::vector<BlendedMove> ready;
  gcode::for_each_block(program, [&](const gcode::Block& b) {
    const MoveInput move = move_input(b, machine_);
    if (!move.curve) {  // a dwell: the motion stops (no blend across it) and stays
      blender_.flush(ready);
      take(ready, events);
      if (b.type == gcode::BlockType::dwell && events.dwell) events.dwell(b.dwell_s, b.location.line);
    } else {
      const auto len = b.length_mm();
      blocks_.push_back({gcode::to_string(b.type), len ? *len : length(*move.curve), move.curve.get()});
      blender_.push(move, corner_tolerance(b, machine_), blocks_.size() - 1, ready);
      take(ready, events);
    }
    if (events.block) events.block(b);
  });
  blender_.flush(ready);
  take(ready, events);
}

}  // namespace kontur::plan
