#include <kontur/gcode/reader.hpp>
#include <kontur/program/block_moves.hpp>
#include <kontur/program/program_path.hpp>

namespace kontur::program {

ProgramPath::ProgramPath(const Machine& machine, bool blend, BlendSpeed speed)
    : machine_(machine), blend_(blend), speed_(std::move(speed)), blender_(blend, &machine, speed_) {}

void ProgramPath::take(std::vector<Move>& ready, const PathHandlers& handlers) {
  for (Move& m : ready) {
    m.id = static_cast<MoveId>(moves_.size());
    moves_.push_back(std::move(m));
    if (handlers.move) handlers.move(moves_.back());
  }
  ready.clear();
}

void ProgramPath::read(const std::string& program, const PathHandlers& handlers) {
  moves_.clear();
  blender_ = CornerBlender(blend_, &machine_, speed_);
  std::vector<Move> ready;
  gcode::for_each_block(program, [&](const gcode::Block& b) {
    Move move = move_of(b, machine_);
    if (!move.curve) {  // a dwell: the motion stops (no blend across it) and stays
      blender_.flush(ready);
      take(ready, handlers);
      if (b.type == gcode::BlockType::dwell && handlers.dwell) handlers.dwell({b.dwell_s, b.location.line});
    } else {
      blender_.push(move, ready);
      take(ready, handlers);
    }
    if (handlers.block) handlers.block(b);
  });
  blender_.flush(ready);
  take(ready, handlers);
}

}  // namespace kontur::program
