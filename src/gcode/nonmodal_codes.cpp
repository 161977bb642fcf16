// The non-modal codes (group 0): G4 dwell, G10 work offsets, G28 / G30 home, G53 machine
// coordinates, the G92 family. The frames themselves are CoordinateFrames.
#include "executor.hpp"

#include <cmath>

namespace kontur::gcode::detail {

bool Executor::run_nonmodal(const BlockCodes& codes) {
  const int g = codes.code(g_nonmodal);
  const int col = codes.column(g_nonmodal);
  switch (g) {
    case 100: g10(col); break;
    case 280: case 300: home(g, col); break;
    case 281: case 301: store_home(g); break;
    case 530: return true;
    case 920: case 921: case 922: case 923: g92(g, col); break;
    default: break;  // G4 ran before the plane (dwell)
  }
  return false;
}

void Executor::dwell(int col) {
  if (!w->has('P')) fail(col, "dwell", "G4: P (dwell time in seconds) missing");
  const double p = w->get('P');
  if (p < 0.0) fail(w->col('P'), "dwell", fmt::format("G4 P{}: dwell time must be >= 0", num(p)));
  Block b = make_block(BlockType::dwell, col);
  b.start = b.end = to_machine(pos);
  b.dwell_s = p;
  emit(std::move(b));
}

void Executor::g10(int col) {
  if (!w->has('L')) fail(col, "g10", "G10: L missing (L2 or L20 set a work offset)");
  const double l = w->get('L');
  if (l == 1.0 || l == 10.0 || l == 11.0 || (rules_.fanuc_offset_registers && (l == 12.0 || l == 13.0))) {
    g10_tool(static_cast<int>(l), col);
    return;
  }
  if (l != 2.0 && l != 20.0) fail(w->col('L'), "g10", fmt::format("G10 L{}: unknown (L2 or L20 set a work offset)", num(l)));
  if (!w->has('P')) fail(col, "g10", "G10: P missing (coordinate system 1..9, 0 = the active one)");
  const double p = w->get('P');
  if (p != std::floor(p) || p < 0.0 || p > 9.0)
    fail(w->col('P'), "g10", fmt::format("G10 P{}: coordinate system must be 0..9", num(p)));
  const int index = p == 0.0 ? modal.work_offset : static_cast<int>(p);
  const Vec3 m = to_machine(pos);
  const ExtraAxes xm = extra_to_machine(xpos);
  const char letters[3] = {'X', 'Y', 'Z'};
  if (w->has('R')) {
    if (l == 20.0) fail(w->col('R'), "g10", "G10 L20: R (rotation) only with L2");
    frames.set_rotation_deg(index, w->get('R'));
  }
  if (l == 2.0) {
    for (int a = 0; a < 3; ++a)
      if (w->has(letters[a])) frames.set_offset(index, a, w->get(letters[a]) * scale());
    for (int i = 0; i < extra_axis_count; ++i)  // the extra axes: plain offsets, never rotated
      if (w->has(extra_axis_letters[i]))
        frames.set_extra_offset(index, i, w->get(extra_axis_letters[i]) * extra_scale(i));
  } else {
    // L20: the offset that makes the current point have the given program coordinates
    Vec3 p_new = pos;
    for (int a = 0; a < 3; ++a)
      if (w->has(letters[a])) p_new[a] = w->get(letters[a]) * scale();
    const Vec3 off = frames.offset_placing(m, p_new, index);
    for (int a = 0; a < 3; ++a)
      if (w->has(letters[a])) frames.set_offset(index, a, off[a]);
    for (int i = 0; i < extra_axis_count; ++i)
      if (w->has(extra_axis_letters[i]))
        frames.set_extra_offset(index, i,
                                frames.extra_offset_placing(i, xm[static_cast<std::size_t>(i)],
                                                            w->get(extra_axis_letters[i]) * extra_scale(i)));
  }
  if (index == modal.work_offset) {
    pos = to_program(m);
    xpos = xto = extra_to_program(xm);
  }
}

void Executor::g10_tool(int l, int col) {
  const std::string name = fmt::format("G10 L{}", l);
  if (!w->has('P')) fail(col, "g10", fmt::format("{}: P (the tool number) missing", name));
  const int n = register_word('P', "the tool number");
  Tool tool = tools_.find(n) != nullptr ? *tools_.find(n) : Tool{n, 0, 0.0, 0.0};
  if (rules_.fanuc_offset_registers && l >= 10) {
    // the Fanuc family: R is the register's value (G91: added to it); L10 / L11 H (length), L12 /
    // L13 D (radius), geometry / wear
    if (!w->has('R')) fail(col, "g10", fmt::format("{}: R (the offset value) missing", name));
    const double v = w->get('R') * scale();
    const bool add = modal.distance == DistanceMode::incremental;
    if (l == 10) tool.length_mm = (add ? tool.length_mm : 0.0) + v;
    if (l == 12) {
      const double r = (add ? tool.diameter_mm / 2.0 : 0.0) + v;
      if (r < 0.0) fail(w->col('R'), "negative-radius", fmt::format("{} R{}: the radius must be >= 0", name, num(w->get('R'))));
      tool.diameter_mm = 2.0 * r;
    }
    if (l == 11 || l == 13) {
      double& wear = (l == 11 ? h_wear_ : d_wear_)[n];
      wear = (add ? wear : 0.0) + v;
    }
    tools_.set(tool);
    return;
  }
  if (w->has('R')) {
    if (w->get('R') < 0.0) fail(w->col('R'), "negative-radius", fmt::format("{} R{}: the radius must be >= 0", name, num(w->get('R'))));
    tool.diameter_mm = 2.0 * w->get('R') * scale();
  }
  if (w->has('Z')) {
    const double z = w->get('Z') * scale();
    if (l == 1) {
      tool.length_mm = z;
    } else {
      // the length that makes the current machine position have Z = z in the program coordinates
      // (L10: with the current work offsets; L11: without them, as in G59.3 without G92)
      const Vec3 m = to_machine(pos);
      Vec3 p = pos;
      p.z() = z;
      tool.length_mm = l == 10 ? m.z() - frames.to_machine(p, modal.work_offset).z() : m.z() - z;
    }
  }
  tools_.set(tool);
}

void Executor::home(int g, int col) {
  const int base = g == 280 ? 5161 : 5181;
  Vec3 home_m(params.numbered(base) * scale(), params.numbered(base + 1) * scale(), params.numbered(base + 2) * scale());
  // the extra axes' home: #5164-#5169 (G28), #5184-#5189 (G30), A B C [deg], U V W in program units
  ExtraAxes home_x{};
  for (int i = 0; i < extra_axis_count; ++i)
    home_x[static_cast<std::size_t>(i)] = params.numbered(base + 3 + i) * extra_scale(i);
  if (has_axes()) {
    // LinuxCNC: a rapid to the intermediate point, then the axes given (only those) to their home
    const Vec3 via = target();
    xto = extra_target();
    line_move(BlockType::rapid, via, col, Feed{});
    Vec3 m = to_machine(pos);
    const char letters[3] = {'X', 'Y', 'Z'};
    for (int a = 0; a < 3; ++a)
      if (w->has(letters[a])) m[a] = home_m[a];
    ExtraAxes xm = extra_to_machine(xpos);
    for (int i = 0; i < extra_axis_count; ++i)
      if (w->has(extra_axis_letters[i])) xm[static_cast<std::size_t>(i)] = home_x[static_cast<std::size_t>(i)];
    xto = extra_to_program(xm);
    line_move(BlockType::rapid, to_program(m), col, Feed{});
  } else {
    xto = extra_to_program(home_x);  // every axis home
    line_move(BlockType::rapid, to_program(home_m), col, Feed{});
  }
}

void Executor::store_home(int g) {
  const Vec3 m = to_machine(pos) / scale();
  const int base = g == 281 ? 5161 : 5181;
  for (int a = 0; a < 3; ++a) params.set_numbered(base + a, m[a]);
  const ExtraAxes xm = extra_to_machine(xpos);
  for (int i = 0; i < extra_axis_count; ++i)
    params.set_numbered(base + 3 + i, xm[static_cast<std::size_t>(i)] / extra_scale(i));
}

void Executor::g92(int g, int col) {
  if (g == 920) {
    if (!has_axes()) fail(col, "axis-words", "G92: axis words missing");
    const char letters[3] = {'X', 'Y', 'Z'};
    for (int a = 0; a < 3; ++a)
      if (w->has(letters[a])) {
        const double v = w->get(letters[a]) * scale();
        frames.shift_g92(a, pos[a], v);
        pos[a] = v;
      }
    for (int i = 0; i < extra_axis_count; ++i)
      if (w->has(extra_axis_letters[i])) {
        const auto k = static_cast<std::size_t>(i);
        const double v = w->get(extra_axis_letters[i]) * extra_scale(i);
        frames.shift_extra_g92(i, xpos[k], v);
        xpos[k] = xto[k] = v;
      }
    frames.save_g92();
    return;
  }
  const Vec3 m = to_machine(pos);
  const ExtraAxes xm = extra_to_machine(xpos);
  if (g == 923) frames.restore_g92();
  else frames.clear_g92(g == 921);
  pos = to_program(m);
  xpos = xto = extra_to_program(xm);
}

}  // namespace kontur::gcode::detail
