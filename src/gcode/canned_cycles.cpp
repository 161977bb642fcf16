// Canned drilling cycles G73, G81, G82, G83 (and in the Fanuc family G84 tapping, G85 boring with
// feed out, G86 boring with rapid out, G89 boring with dwell and feed out) with G98 / G99, expanded
// into rapid and feed moves.
#include "executor.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kontur::gcode::detail {

void Executor::cycle(int motion, int col) {
  const std::string word = g_name(motion);
  const int cycle_number = motion / 10;
  if (modal.plane != Plane::xy) fail(col, "cycle-plane", fmt::format("{}: canned cycles only in the XY plane (G17)", word));
  if (modal.feed_mode == FeedMode::inverse_time)
    fail(col, "cycle-feed-mode", fmt::format("{}: canned cycles not allowed with G93 (inverse time)", word));
  const Feed feed = feed_move(word);
  const double s = scale();
  if (w->has('R')) {
    cycle_r = w->get('R') * s;
    cycle_r_set = true;
  }
  if (w->has('Z')) {
    cycle_z = w->get('Z') * s;
    cycle_z_set = true;
  }
  if (w->has('Q')) {
    cycle_q = w->get('Q') * s;
    cycle_q_set = true;
  }
  if (w->has('P')) cycle_p = w->get('P');
  if (!cycle_z_set) fail(col, "cycle-words", fmt::format("{}: Z (hole bottom) missing", word));
  if (!cycle_r_set) fail(col, "cycle-words", fmt::format("{}: R (retract plane) missing", word));
  if ((motion == 730 || motion == 830) && !(cycle_q_set && cycle_q > 0.0))
    fail(w->has('Q') ? w->col('Q') : col, "cycle-peck", fmt::format("{}: Q (peck depth) missing or not > 0", word));
  if (cycle_p < 0.0) fail(w->col('P'), "cycle-words", fmt::format("{} P{}: dwell must be >= 0", word, num(cycle_p)));
  int repeats = 1;
  // Fanuc 0i / 30i write the repeat count as K (older controls: L)
  const char repeat_letter = rules_.fanuc_cycles && !w->has('L') && w->has('K') ? 'K' : 'L';
  if (w->has(repeat_letter)) {
    const double l = w->get(repeat_letter);
    if (l != std::floor(l) || l < 0.0 || l > tolerances::gcode_max_cycle_repeats)
      fail(w->col(repeat_letter), "cycle-repeat", fmt::format("{} {}{}: repeats must be an integer 0..{}", word, repeat_letter, num(l), tolerances::gcode_max_cycle_repeats));
    repeats = static_cast<int>(l);
  }
  if (motion == 840 && !tapping_warned) {
    tapping_warned = true;
    warn(col, "G84: tapping is read as a feed to the bottom and a feed back to R at F; the spindle's "
              "synchronisation and reversal are not modelled (warned once)");
  }
  const bool incremental = modal.distance == DistanceMode::incremental;
  const double r_plane = incremental ? pos.z() + cycle_r : cycle_r;
  const double bottom = incremental ? r_plane + cycle_z : cycle_z;
  if (bottom > r_plane)
    fail(col, "cycle-depth", fmt::format("{}: the hole bottom Z {} mm is above the retract plane R {} mm", word, num(bottom), num(r_plane)));
  if (motion == 730 || motion == 830) {
    const double pecks = (r_plane - bottom) / cycle_q;
    if (pecks > tolerances::gcode_max_pecks)
      fail(w->has('Q') ? w->col('Q') : col, "cycle-peck", fmt::format("{}: Q {} mm gives more than {} pecks", word, num(cycle_q), tolerances::gcode_max_pecks));
  }
  {
    const double pecks = (motion == 730 || motion == 830) ? std::ceil((r_plane - bottom) / cycle_q) : 1.0;
    if (repeats * (pecks * 3.0 + 4.0) > tolerances::gcode_max_cycle_moves)
      fail(col, "cycle-repeat", fmt::format("{}: L{} holes of {} pecks expand into more than {} moves", word, repeats,
                                            num(pecks), tolerances::gcode_max_cycle_moves));
  }
  const double clear_z = modal.retract == RetractMode::initial_z ? std::max(cycle_old_z, r_plane) : r_plane;
  auto rapid_to = [&](const Vec3& p) {
    if ((p - pos).norm() > 0.0) line_move(BlockType::rapid, p, col, Feed{}, cycle_number);
  };
  auto feed_to = [&](const Vec3& p) { line_move(BlockType::line, p, col, feed, cycle_number); };
  if (pos.z() < r_plane) rapid_to(Vec3(pos.x(), pos.y(), r_plane));
  const double delta = tolerances::gcode_peck_clearance_mm;
  for (int rep = 0; rep < repeats; ++rep) {
    Vec3 hole = pos;
    const char letters[2] = {'X', 'Y'};
    for (int a = 0; a < 2; ++a)
      if (w->has(letters[a])) {
        const double v = w->get(letters[a]) * s;
        hole[a] = incremental ? pos[a] + v : v;
      }
    rapid_to(Vec3(hole.x(), hole.y(), pos.z()));
    rapid_to(Vec3(hole.x(), hole.y(), r_plane));
    if (motion != 730 && motion != 830) {
      feed_to(Vec3(hole.x(), hole.y(), bottom));
      // G82, G89 dwell at the bottom; G84 too when P is given
      if (motion == 820 || motion == 890 || (motion == 840 && cycle_p > 0.0)) {
        Block b = make_block(BlockType::dwell, col);
        b.start = b.end = to_machine(pos);
        b.dwell_s = cycle_p;
        b.canned_cycle = cycle_number;
        emit(std::move(b));
      }
      // G84, G85, G89 feed back out to R (G86, like G81 and G82, leaves at rapid)
      if (motion == 840 || motion == 850 || motion == 890) feed_to(Vec3(hole.x(), hole.y(), r_plane));
    } else {
      double depth = r_plane;
      while (depth > bottom) {
        depth = std::max(depth - cycle_q, bottom);
        feed_to(Vec3(hole.x(), hole.y(), depth));
        if (depth <= bottom) break;
        if (motion == 830) {
          rapid_to(Vec3(hole.x(), hole.y(), r_plane));
          rapid_to(Vec3(hole.x(), hole.y(), depth + delta));
        } else {
          rapid_to(Vec3(hole.x(), hole.y(), std::min(depth + delta, r_plane)));
        }
      }
    }
    rapid_to(Vec3(hole.x(), hole.y(), clear_z));
  }
}

}  // namespace kontur::gcode::detail
