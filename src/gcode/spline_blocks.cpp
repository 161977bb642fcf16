// Spline blocks: LinuxCNC G5 / G5.1 Beziers, G5.2 / G5.3 NURBS, and the G06.2 / G6.2 NURBS of
// Fanuc, Mitsubishi and LinuxCNC, collected over several blocks, checked like a control and
// built as NurbsCurve.
#include "executor.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kontur::gcode::detail {

void Executor::bezier(bool cubic, const Vec3& to, int col) {
  const std::string word = cubic ? "G5" : "G5.1";
  if (modal.plane != Plane::xy) fail(col, "bezier-plane", fmt::format("{}: only in the XY plane (G17)", word));
  const Feed feed = feed_move(word);
  const bool has_i = w->has('I'), has_j = w->has('J'), has_p = w->has('P'), has_q = w->has('Q');
  if (w->has('K')) fail(w->col('K'), "bezier-words", fmt::format("{}: K not allowed (XY plane: I J)", word));
  if (has_i != has_j) fail(col, "bezier-words", fmt::format("{}: I and J must be given together", word));
  Vec3 ij = Vec3::Zero();
  if (has_i) ij = Vec3(w->get('I') * scale(), w->get('J') * scale(), 0.0);
  std::vector<Vec3> pts;
  const Vec3 dz(0.0, 0.0, to.z() - pos.z());
  if (cubic) {
    if (!has_p || !has_q)
      fail(col, "bezier-pq-missing", "G5: P and Q missing (second control point, offset from the end point)");
    if (!has_i) {
      if (!prev_g5)
        fail(col, "bezier-ij-missing",
             "G5: I and J missing (first control point, offset from the start; only a G5 directly after a G5 may "
             "omit them)");
      ij = -prev_g5_pq;
    }
    const Vec3 pq(w->get('P') * scale(), w->get('Q') * scale(), 0.0);
    pts = {pos, pos + ij + dz / 3.0, to + pq - dz / 3.0, to};
    prev_g5 = true;
    prev_g5_pq = pq;
  } else {
    if (!has_i) fail(col, "bezier-ij-missing", "G5.1: I and J missing (the control point, offset from the start)");
    if (has_p || has_q) fail(col, "bezier-words", "G5.1: P and Q not allowed (quadratic: one control point I J)");
    pts = {pos, pos + ij + dz / 2.0, to};
    prev_g5 = false;
  }
  NurbsData d;
  d.degree = static_cast<int>(pts.size()) - 1;
  d.knots.assign(pts.size(), 0.0);
  d.knots.resize(2 * pts.size(), 1.0);
  for (auto& p : pts) d.points.push_back(to_machine(p));
  Block b = make_block(BlockType::bezier, col);
  b.start = to_machine(pos);
  b.end = to_machine(to);
  b.feed = feed;
  b.geometry.emplace<NurbsCurve>(at(col, word, [&] { return NurbsCurve(std::move(d)); }));
  emit(std::move(b));
  pos = to;
}

void Executor::start_g52(int col) {
  spline = Spline::g52;
  spline_loc = location(col);
  spline_word = "G5.2";
  spline_feed = feed_move("G5.2");
  spline_modal = modal;
  spline_start = pos;
  nurbs = NurbsData{};
  rank = 3;
  if (w->has('L')) {
    const double l = w->get('L');
    if (l != std::floor(l) || l < 2.0 || l > tolerances::max_degree + 1)
      fail(w->col('L'), "nurbs-order", fmt::format("G5.2 L{}: order outside the supported range 2..{}", num(l), tolerances::max_degree + 1));
    rank = static_cast<int>(l);
  }
  const double weight = w->has('P') ? w->get('P') : 1.0;
  if (!(weight > 0.0)) fail(w->col('P'), "nurbs-weight", fmt::format("G5.2 P{}: weight must be > 0", num(weight)));
  last_point = pos;
  if (has_axes()) {
    add_control_point(pos, 1.0);
    add_control_point(target(), weight);
  } else {
    add_control_point(pos, weight);
  }
}

void Executor::add_control_point(const Vec3& p, double weight) {
  if (static_cast<int>(nurbs.points.size()) >= tolerances::gcode_max_spline_points)
    fail(block_column(), "nurbs-size", fmt::format("{}: more than {} control points", spline_word, tolerances::gcode_max_spline_points));
  nurbs.points.push_back(p);
  nurbs.weights.push_back(weight);
  last_point = p;
}

void Executor::finish_g52() {
  const int n = static_cast<int>(nurbs.points.size());
  if (n < rank)
    fail_spline("nurbs-points", fmt::format("G5.2: {} control points (with the start point), order L{} needs at least {}",
                                            n, rank, rank));
  nurbs.degree = rank - 1;
  nurbs.knots.clear();
  for (int i = 0; i < rank; ++i) nurbs.knots.push_back(0.0);
  for (int i = 1; i <= n - rank; ++i) nurbs.knots.push_back(i);
  for (int i = 0; i < rank; ++i) nurbs.knots.push_back(n - rank + 1);
  emit_spline(BlockType::nurbs);
}

void Executor::emit_spline(BlockType type) {
  Block b;
  b.type = type;
  b.modal = spline_modal;
  b.location = spline_loc;
  b.frame_linear = rotation();
  b.frame_origin = to_machine(Vec3::Zero());
  b.feed = spline_feed;
  b.start = to_machine(spline_start);
  const Vec3 end_program = nurbs.points.back();
  for (auto& p : nurbs.points) p = to_machine(p);
  b.end = nurbs.points.back();
  if (const auto problem = validate(nurbs))
    fail_spline(problem->rule.c_str(), fmt::format("{}: {}", spline_word, problem->message));
  try {
    b.geometry.emplace<NurbsCurve>(std::move(nurbs));
  } catch (const InputError& e) {
    fail_spline(e.rule().c_str(), fmt::format("{}: {}", spline_word, e.what()));
  }
  nurbs = NurbsData{};
  spline = Spline::none;
  emit(std::move(b));
  pos = end_program;
}

void Executor::start_g62(int col, int motion_word) {
  bool leading_zero = false;
  for (int i = 0; i < w->g_count; ++i)
    if (w->g[static_cast<std::size_t>(i)] == 62) leading_zero = w->g_leading_zero[static_cast<std::size_t>(i)] != 0;
  spline_word = motion_word == 62 ? (leading_zero ? "G06.2" : "G6.2") : "G6.2";
  if (!w->has('K')) fail(col, "nurbs-knot-missing", fmt::format("{}: K (knot) missing in the first block of the curve", spline_word));
  spline = Spline::g62;
  spline_loc = location(col);
  spline_feed = feed_move(spline_word);
  spline_modal = modal;
  spline_start = pos;
  nurbs = NurbsData{};
  knot_line.clear();
  end_knots = 0;
  rank = 4;
  if (w->has('P')) {
    const double p = w->get('P');
    if (p != std::floor(p) || p < 2.0 || p > tolerances::max_degree + 1)
      fail(w->col('P'), "nurbs-rank",
           fmt::format("{} P{}: rank outside the supported range 2..{} (rank = degree + 1; Fanuc accepts 2..4)",
                       spline_word, num(p), tolerances::max_degree + 1));
    rank = static_cast<int>(p);
  }
  if (w->has('Q') && !q_warned) {
    q_warned = true;
    warn(w->col('Q'), fmt::format("{} Q{}: LinuxCNC's approximation by biarcs, arcs or lines is replaced by true spline "
                                 "interpolation",
                                 spline_word, num(w->get('Q'))));
  }
  const Vec3 first = target();
  if ((first - pos).norm() > tolerances::gcode_same_point_mm)
    fail(col, "nurbs-first-point",
         fmt::format("{}: the first control point {} is not the current position {} (distance {} mm)", spline_word,
                     point_text(first), point_text(pos), num((first - pos).norm())));
  last_point = pos;
  add_knot(w->get('K'), w->col('K'));
  add_control_point(pos, weight_word());
}

double Executor::weight_word() const {
  const double r = w->has('R') ? w->get('R') : 1.0;
  if (!(r > 0.0)) fail(w->col('R'), "nurbs-weight", fmt::format("{}: weight R{} must be > 0", spline_word, num(r)));
  return r;
}

void Executor::add_knot(double k, int col) {
  if (!nurbs.knots.empty() && k < nurbs.knots.back())
    fail(col, "knots-decreasing",
         fmt::format("{}: knot K{} is less than the previous knot K{} (line {}): knots must not decrease", spline_word,
                     num(k), num(nurbs.knots.back()), knot_line.back()));
  if (static_cast<int>(nurbs.knots.size()) > tolerances::gcode_max_spline_points + tolerances::max_degree + 1)
    fail(col, "nurbs-size", fmt::format("{}: too many knots", spline_word));
  nurbs.knots.push_back(k);
  knot_line.push_back(diag.line());
}

void Executor::finish_g62() {
  const int np = static_cast<int>(nurbs.points.size());
  const int nk = static_cast<int>(nurbs.knots.size());
  const auto& k = nurbs.knots;
  if (nk != np + rank)
    fail_spline("knot-count", fmt::format("{}: {} knots given, {} needed ({} control points + rank {})", spline_word, nk,
                                          np + rank, np, rank));
  if (np < rank)
    fail_spline("nurbs-points", fmt::format("{}: {} control points, rank {} needs at least {}", spline_word, np, rank, rank));
  for (int i = 1; i < rank; ++i)
    if (k[static_cast<std::size_t>(i)] != k[0])
      fail_spline("end-knots", fmt::format("{}: the first {} knots must be equal (rank {}): knot {} is K{}, knot 1 is K{}",
                                           spline_word, rank, rank, i + 1, num(k[static_cast<std::size_t>(i)]), num(k[0])));
  for (int i = nk - rank; i < nk - 1; ++i)
    if (k[static_cast<std::size_t>(i)] != k.back())
      fail_spline("end-knots", fmt::format("{}: the last {} knots must be equal (rank {}): knot {} is K{}, knot {} is K{}",
                                           spline_word, rank, rank, i + 1, num(k[static_cast<std::size_t>(i)]), nk,
                                           num(k.back())));
  if (!(k.back() > k.front()))
    fail_spline("knot-range", fmt::format("{}: all knots are equal (K{}): the parameter range is empty", spline_word, num(k[0])));
  for (int i = rank; i < nk - rank;) {
    int j = i;
    while (j + 1 < nk - rank && k[static_cast<std::size_t>(j + 1)] == k[static_cast<std::size_t>(i)]) ++j;
    const int mult = j - i + 1;
    if (mult >= rank)
      fail_spline("inner-knot-multiplicity",
                  fmt::format("{}: inner knot K{} repeated {} times (line {}); at most rank - 1 = {}", spline_word,
                              num(k[static_cast<std::size_t>(i)]), mult, knot_line[static_cast<std::size_t>(i)], rank - 1));
    i = j + 1;
  }
  nurbs.degree = rank - 1;
  emit_spline(BlockType::nurbs);
}

bool Executor::continue_spline() {
  if (spline == Spline::g52) {
    bool closes = false;
    for (int i = 0; i < w->g_count; ++i) {
      if (w->g[static_cast<std::size_t>(i)] == 53) closes = true;
      else
        fail(w->g_column[static_cast<std::size_t>(i)], "g52-open",
             fmt::format("{}: not allowed inside an open G5.2 NURBS block (close it with G5.3 first)",
                         g_name(w->g[static_cast<std::size_t>(i)])));
    }
    if (w->m_count > 0)
      fail(w->m_column[0], "g52-open", fmt::format("M{}: not allowed inside an open G5.2 NURBS block (close it with G5.3 first)", w->m[0]));
    check_spline_words("XYZPF", closes ? "G5.3" : "G5.2");
    if (w->has('F')) update_feed();
    if (has_axes()) {
      if (closes) fail(block_column(), "g53-axes", "G5.3: axis words not allowed (G5.3 only closes the NURBS block)");
      const double weight = w->has('P') ? w->get('P') : 1.0;
      if (!(weight > 0.0)) fail(w->col('P'), "nurbs-weight", fmt::format("G5.2: weight P{} must be > 0", num(weight)));
      add_control_point(target(), weight);
    } else if (w->has('P')) {
      fail(w->col('P'), "g52-words", "G5.2: P (weight) without a control point X Y Z");
    }
    if (closes) {
      finish_g52();
      modal.motion_g10 = motion_none;
    }
    return true;
  }
  // G6.2: K with or without axes; a G6.2 word only on K-alone blocks (LinuxCNC's closing blocks)
  if (!w->has('K') || w->m_count > 0 || w->keyword != Keyword::none) return false;
  for (int i = 0; i < w->g_count; ++i)
    if (w->g[static_cast<std::size_t>(i)] != 62) return false;
  if (w->g_count > 0 && has_axes()) return false;  // G6.2 with a point: a new curve
  check_spline_words("KXYZRF", spline_word.c_str());
  if (w->has('F')) update_feed();
  if (has_axes()) {
    if (end_knots > 0)
      fail(block_column(), "nurbs-point-after-end-knots",
           fmt::format("{}: control point after the end knots (K-alone blocks close the curve)", spline_word));
    add_knot(w->get('K'), w->col('K'));
    const double weight = weight_word();
    Vec3 p = last_point;
    const char letters[3] = {'X', 'Y', 'Z'};
    for (int a = 0; a < 3; ++a)
      if (w->has(letters[a])) {
        const double v = w->get(letters[a]) * scale();
        p[a] = modal.distance == DistanceMode::absolute ? v : last_point[a] + v;
      }
    add_control_point(p, weight);
  } else {
    if (w->has('R')) fail(w->col('R'), "nurbs-words", fmt::format("{}: R (weight) without a control point", spline_word));
    add_knot(w->get('K'), w->col('K'));
    ++end_knots;
  }
  return true;
}

void Executor::check_spline_words(const char* allowed, const char* word) const {
  for (int c = 0; c < 26; ++c) {
    const char letter = static_cast<char>('A' + c);
    if (w->has(letter) && extra_axis_index(letter) >= 0)
      fail(w->col(letter), "unsupported",
           fmt::format("{} {}: extra axes (A B C U V W) are not supported in a spline: its control points are X Y Z "
                       "(move the extra axes in a block of their own)",
                       word, word_text(letter)));
    if (w->has(letter) && !std::strchr(allowed, letter))
      fail(w->col(letter), "nurbs-words", fmt::format("{}: {} not allowed in a control point block", word, letter));
  }
}

void Executor::update_feed() {
  const double f = w->get('F');
  if (f < 0.0) fail(w->col('F'), "feed-range", fmt::format("F{}: feed must be >= 0", num(f)));
  if (modal.feed_mode == FeedMode::units_per_minute) feed_mm_per_min = f * scale();
}

}  // namespace kontur::gcode::detail
