// Sinumerik's drilling cycles CYCLE81 (drilling), CYCLE82 (with a dwell at the bottom) and CYCLE83
// (deep-hole drilling), called once or modally (MCALL), expanded into the blocks they run at the
// current X Y position (G17, tool along Z): G0 to the reference plane plus the safety distance, G1
// to the depth (in steps for CYCLE83), G0 back to the retract plane. Z is absolute whatever G90 /
// G91 say (the cycle's planes are absolute); the G0 / G1 / G2 / G3 mode before the cycle is the
// motion mode after it (the cycles keep the caller's modal state).
#include <algorithm>
#include <cmath>
#include <kontur/tolerances.hpp>

#include "message_format.hpp"
#include "sinumerik_front_end.hpp"

namespace kontur::gcode::detail {

std::vector<std::optional<double>> SinumerikFrontEnd::cycle_arguments(Cursor& c, std::string_view name) {
  std::vector<std::optional<double>> a;
  if (!c.eat('(')) fail(c.col(), "syntax", fmt::format("{}: '(' and the cycle's parameters expected", name));
  if (c.eat(')')) return a;
  for (;;) {
    if (c.peek() == ',' || c.peek() == ')')
      a.emplace_back();
    else if (c.peek() == '"') {
      (void)string_literal(c);
      a.emplace_back();
    } else
      a.emplace_back(expr(c));
    if (c.eat(')')) break;
    if (!c.eat(',')) fail(c.col(), "syntax", fmt::format("{}(: ',' or ')' expected", name));
  }
  return a;
}

bool SinumerikFrontEnd::cycle_call(std::string_view name, Cursor& c, int col, Words& words) {
  (void)words;
  const auto args = cycle_arguments(c, name);
  expand_cycle(name, args, col);
  return true;
}

void SinumerikFrontEnd::expand_cycle(std::string_view name, const std::vector<std::optional<double>>& a, int col) {
  auto arg = [&](std::size_t i) -> std::optional<double> { return i < a.size() ? a[i] : std::nullopt; };
  if (plane_g != 170)
    fail(col, "cycle-plane",
         fmt::format("{}: drilling cycles only in the XY plane (G17) in Kontur (dialect sinumerik)", name));
  if (!arg(0) || !arg(1))
    fail(col, "cycle-words", fmt::format("{}: RTP (retract plane) and RFP (reference plane) are needed", name));
  const double rtp = *arg(0), rfp = *arg(1);
  const double sdis = std::abs(arg(2).value_or(0.0));
  double dp = 0.0;
  if (arg(4))
    dp = rfp - std::abs(*arg(4));  // DPR wins over DP, as on the control
  else if (arg(3))
    dp = *arg(3);
  else
    fail(col, "cycle-words", fmt::format("{}: DP (depth) or DPR (depth below the reference plane) missing", name));
  const double start = rfp + sdis;
  if (!(dp < start))
    fail(col, "cycle-depth",
         fmt::format("{}: the depth {} is not below the reference plane plus safety distance {}", name, num(dp),
                     num(start)));
  if (rtp < start)
    fail(col, "cycle-depth",
         fmt::format("{}: the retract plane {} is below the reference plane plus safety distance {}", name, num(rtp),
                     num(start)));
  auto move = [&](int g, double z) {
    Words w;
    w.add_g(g, col);
    w.set('Z', z, col);
    w.absolute_words |= 1u << ('Z' - 'A');
    w.first_column = col;
    pending.push_back(w);
  };
  auto dwell = [&](double s) {
    if (!(s > 0.0)) return;
    Words w;
    w.add_g(40, col);
    w.set('P', s, col);
    w.first_column = col;
    pending.push_back(w);
  };
  const std::size_t first = pending.size();
  move(0, start);
  if (name == "CYCLE81" || name == "CYCLE82") {
    move(10, dp);
    if (name == "CYCLE82") dwell(arg(5).value_or(0.0));
  } else {  // CYCLE83
    const double dtb = arg(8).value_or(0.0), dts = arg(9).value_or(0.0);
    const int vari = static_cast<int>(arg(11).value_or(0.0));
    if (vari != 0 && vari != 1)
      fail(col, "cycle-words", fmt::format("CYCLE83: VARI={}: 0 (chip breaking) or 1 (chip removal)", vari));
    const double dam = std::abs(arg(7).value_or(0.0));
    double first_depth = dp;
    if (arg(6))
      first_depth = rfp - std::abs(*arg(6));  // FDPR wins over FDEP
    else if (arg(5))
      first_depth = *arg(5);
    first_depth = std::max(first_depth, dp);
    double step = rfp - first_depth;
    if (!(step > 0.0)) fail(col, "cycle-peck", "CYCLE83: the first drilling depth is not below the reference plane");
    const double total = rfp - dp;
    if (total / std::max(std::min(step, dam > 0.0 ? dam : step), 1e-9) > tolerances::gcode_max_pecks)
      fail(col, "cycle-peck", fmt::format("CYCLE83: more than {} drilling steps", tolerances::gcode_max_pecks));
    const double unit = inch ? 1.0 / 25.4 : 1.0;
    // anticipation distance of chip removal: 0.6 mm up to 30 mm of depth, else depth / 50, at most 7 mm
    const double total_mm = total / unit;
    const double anticipation = (total_mm <= 30.0 ? 0.6 : std::min(total_mm / 50.0, 7.0)) * unit;
    const double retract = (arg(14) && *arg(14) > 0.0 ? *arg(14) : 1.0 * unit);  // chip breaking: _VRT, else 1 mm
    double depth = rfp;
    bool first_step = true;
    while (depth > dp) {
      if (!first_step) step = dam > 0.0 ? std::max(step - dam, dam) : step;
      const double next = std::max(depth - step, dp);
      move(10, next);
      dwell(dtb);
      depth = next;
      first_step = false;
      if (depth <= dp) break;
      if (vari == 1) {
        move(0, start);
        dwell(dts);
        move(0, depth + anticipation);
      } else {
        move(0, std::min(depth + retract, start));
      }
    }
  }
  move(0, rtp);
  if (motion_g >= 0 && motion_g <= 30) {  // the motion mode of the caller again (not after CIP / CT)
    Words w;
    w.add_g(motion_g, col);
    w.first_column = col;
    pending.push_back(w);
  }
  if (pending.size() - first > static_cast<std::size_t>(tolerances::gcode_max_cycle_moves))
    fail(col, "cycle-repeat", fmt::format("{}: more than {} moves", name, tolerances::gcode_max_cycle_moves));
}

}  // namespace kontur::gcode::detail
