#pragma once
// From a G-code block to a move: the block's curve (NURBS and Beziers as span polynomials, which
// evaluate faster), its path feed [mm/s] on the machine, its corner tolerance and its length.
#include <kontur/gcode/block.hpp>
#include <kontur/machine.hpp>
#include <kontur/program/move.hpp>

namespace kontur::program {

/// The move of block `b` on `machine` (its id is not set yet): curve (nullptr for a block without
/// motion, e.g. a dwell), feed [mm/s] (rapid: the machine's rapid feed; G93: the block's length
/// over its duration), exact stop (G61 / G61.1), corner tolerance (corner_tolerance), source
/// line, type and length. Throws InputError ("feed-missing") for a feed move without a feed.
[[nodiscard]] Move move_of(const gcode::Block& b, const Machine& machine);

/// The G64 tolerance at the end of block `b` [mm]: its P word if given, else the machine's
/// path tolerance; 0 under G61 / G61.1 (no blending).
[[nodiscard]] double corner_tolerance(const gcode::Block& b, const Machine& machine);

}  // namespace kontur::program
