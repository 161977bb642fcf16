#include <kontur/gcode/reader.hpp>
#include <kontur/program/block_moves.hpp>
#include <kontur/program/program_path.hpp>

namespace kontur::program {

ProgramPath::ProgramPath(const Machine& machine, bool blend, bool smooth, BlendSpeed speed, JunctionSpeed junction)
    : machine_(machine),
      blend_(blend),
      smooth_(smooth),
      speed_(std::move(speed)),
      junction_(std::move(junction)),
      smoother_(smooth),
      blender_(blend, &machine, speed_, junction_) {}

void ProgramPath::take(std::vector<Move>& ready, const PathHandlers& handlers) {
  for (Move& m : ready) {
    m.id = static_cast<MoveId>(moves_.size());
    moves_.push_back(std::move(m));
    if (handlers.move) handlers.move(moves_.back());
  }
  ready.clear();
}

void ProgramPath::read(const std::string& program, const PathHandlers& handlers, const gcode::ReaderOptions& reader) {
  read(gcode::validate_program(program, reader), handlers);
}

void ProgramPath::read(const gcode::ValidatedProgram& program, const PathHandlers& handlers) {
  moves_.clear();
  smoother_ = LineSmoother(smooth_);
  blender_ = CornerBlender(blend_, &machine_, speed_, junction_);
  std::vector<Move> ready;
  // The smoother's output goes through the blender, in order.
  auto blend = [&] {
    for (const Move& m : smoothed_) blender_.push(m, ready);
    smoothed_.clear();
  };
  dialect_ = program.dialect;
  gcode::for_each_validated_block(program, [&](const gcode::Block& b) {
    Move move = move_of(b, machine_);
    if (!move.curve) {  // a dwell: the motion stops (no smoothing or blend across it) and stays
      smoother_.flush(smoothed_);
      blend();
      blender_.flush(ready);
      take(ready, handlers);
      if (b.type == gcode::BlockType::dwell && handlers.dwell) handlers.dwell({b.dwell_s, b.location.line});
    } else {
      smoother_.push(move, smoothed_);
      blend();
      take(ready, handlers);
    }
    if (handlers.block) handlers.block(b);
  });
  smoother_.flush(smoothed_);
  blend();
  blender_.flush(ready);
  take(ready, handlers);
}

}  // namespace kontur::program
