#include <kontur/geometry/length.hpp>

#include "gauss_kronrod_rules.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kontur {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct GkResult {
  double value;  // integral [mm]
  double error;  // estimated absolute error [mm]
  double magnitude;  // integral of |f| [mm] (the scale of the rounding)
  int level;     // Patterson level of the value (0: 7 points .. 3: 63 points)
  bool ok;       // the tolerance was met
};

using Rules = detail::PattersonRules;

// One panel [a, b] by the nested Gauss-Kronrod-Patterson rules 7 -> 15 -> 31 -> 63 points: each
// level adds new nodes and reuses every value before it. After each level the difference to the
// previous one estimates the previous (lower-order) value's error; the higher-order value is
// returned, so the estimate bounds its error from above for the smooth speed of a span. The
// estimate never goes below 50 machine epsilons of the integral of |f| (rounding of the sums).
// The values of |C'| at a panel's nodes so far: fsum[i] = f(c - h x_i) + f(c + h x_i) (fsum[0] =
// f(c)), fabs_sum likewise of |f|; entries 0 .. filled - 1 are set.
struct PanelValues {
  std::array<double, Rules::nodes.size()> fsum{};
  std::array<double, Rules::nodes.size()> fabs_sum{};
  int filled = 0;
};

// Fills the nodes of [a, b] up to `used` entries.
void fill_nodes(const Curve& curve, double a, double b, int used, PanelValues& pv, long& evaluations) noexcept {
  const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
  if (pv.filled == 0) {
    pv.fsum[0] = curve.speed(centre);
    pv.fabs_sum[0] = std::abs(pv.fsum[0]);
    evaluations += 1;
    pv.filled = 1;
  }
  for (; pv.filled < used; ++pv.filled) {
    const auto i = static_cast<std::size_t>(pv.filled);
    const double dx = half * Rules::nodes[i];
    const double f1 = curve.speed(centre - dx), f2 = curve.speed(centre + dx);
    pv.fsum[i] = f1 + f2;
    pv.fabs_sum[i] = std::abs(f1) + std::abs(f2);
    evaluations += 2;
  }
}

// The nested levels from `first_level` on (first_level >= 1 needs the value of the level before
// it, `previous`, and its nodes in pv).
GkResult patterson_levels(const Curve& curve, double a, double b, double rel_tol, long& evaluations,
                          PanelValues& pv, int first_level, double previous) noexcept {
  const double half = 0.5 * (b - a);
  GkResult r{0.0, 0.0, 0.0, 0, false};
  for (int level = first_level; level < Rules::levels; ++level) {
    const int used = Rules::used[static_cast<std::size_t>(level)];
    fill_nodes(curve, a, b, used, pv, evaluations);
    const auto& w = Rules::weights[static_cast<std::size_t>(level)];
    double q = 0.0, qabs = 0.0;
    for (int i = 0; i < used; ++i) {
      q += w[static_cast<std::size_t>(i)] * pv.fsum[static_cast<std::size_t>(i)];
      qabs += w[static_cast<std::size_t>(i)] * pv.fabs_sum[static_cast<std::size_t>(i)];
    }
    q *= half;
    qabs *= std::abs(half);
    if (level > 0) {
      const double err = std::max(std::abs(q - previous), 50.0 * kEps * qabs);
      r = {q, err, qabs, level, err <= rel_tol * std::abs(q)};
      if (r.ok) return r;
    }
    previous = q;
  }
  return r;
}

GkResult patterson_panel(const Curve& curve, double a, double b, double rel_tol, long& evaluations) noexcept {
  PanelValues pv;
  return patterson_levels(curve, a, b, rel_tol, evaluations, pv, 0, 0.0);
}

// Length [mm] of a short step [a, b] of one table interval, the speeds va, vb at its ends being
// known: the 7-point Gauss rule (degree 13), accepted when its companion with the ends (degree 7,
// the same inner values) agrees with it to tolerances::step_gauss_agreement; the companion's error
// is of order h^8 against the Gauss rule's h^14, so the Gauss value is then exact to about the
// square of that agreement. Otherwise the nested rules from 15 points on, reusing the 7 values,
// up to the level where two agree to rel_tol.
double step_length(const Curve& curve, double a, double b, double va, double vb, double rel_tol) noexcept {
  PanelValues pv;
  long unused = 0;
  fill_nodes(curve, a, b, Rules::used[0], pv, unused);
  const double half = 0.5 * (b - a);
  const auto& w = Rules::weights[0];
  const auto& c = Rules::gauss_companion_with_ends;
  double gauss = 0.0, companion = c[static_cast<std::size_t>(Rules::used[0])] * (va + vb);
  for (int i = 0; i < Rules::used[0]; ++i) {
    gauss += w[static_cast<std::size_t>(i)] * pv.fsum[static_cast<std::size_t>(i)];
    companion += c[static_cast<std::size_t>(i)] * pv.fsum[static_cast<std::size_t>(i)];
  }
  gauss *= half;
  companion *= half;
  // |C'| >= 0, so the value is also the scale of its rounding.
  if (std::abs(gauss - companion) <= tolerances::step_gauss_agreement * std::abs(gauss)) return gauss;
  return patterson_levels(curve, a, b, rel_tol, unused, pv, 1, gauss).value;
}


// Adaptive bisection of a piece [a, b] whose first panel `r` is already computed; calls
// accept(a, b, result) for every accepted panel, in order. A panel is accepted when its error is
// within rel_tol of its own value, or within its share of the piece's budget: rel_tol times the
// piece's first estimate, times the panel's fraction of the piece's width (abs_density is that
// budget per unit of u). The second test keeps the total error below rel_tol of the piece's
// length where the curve hardly moves (near a cusp, |C'| ~ 0, the relative test alone asks for
// ever more panels, since |C'| there is mostly rounding noise).
template <class Accept>
void adaptive(const Curve& curve, double a, double b, const GkResult& r, double rel_tol, double abs_density,
              int depth, long& evaluations, long evaluation_limit, Accept&& accept) {
  const double mid = 0.5 * (a + b);
  // A panel only a few hundred ulps of u wide cannot be resolved further: the nodes' positions
  // are quantised, so the value there is as good as double precision allows.
  const bool small = !(mid > a && mid < b) || (b - a) <= 256.0 * kEps * std::max(std::abs(a), std::abs(b));
  const bool within_budget = r.error <= abs_density * (b - a);
  if (r.ok || within_budget || depth >= tolerances::gauss_kronrod_max_depth || small ||
      evaluations >= evaluation_limit) {
    GkResult accepted = r;
    accepted.ok = r.ok || within_budget;
    accept(a, b, accepted);
    return;
  }
  GkResult left = patterson_panel(curve, a, mid, rel_tol, evaluations);
  GkResult right = patterson_panel(curve, mid, b, rel_tol, evaluations);
  // Round-off: on a polynomial or rational curve |C'|^2 has only roots of even order, so a real
  // feature (a cusp: |C'| ~ |u - u0|) makes the halves' error at most about a quarter of the
  // parent's. If bisection does not get below three quarters, the estimate is the integrand's
  // rounding noise (e.g. weights 1e-4..1e4, where the quotient rule cancels large terms): accept
  // the halves as they are, not converged, instead of bisecting noise down to depth 40.
  // A narrow feature that the panels do not resolve yet (a spike of a heavily weighted NURBS)
  // also stops the error from shrinking for a few levels, but its error is of the order of the
  // panel's value; noise is not: it is also required to be below
  // tolerances::gauss_kronrod_noise_relative of the panel's |f|. And noise is spread over the
  // panel, while a feature sits in one half (a spike at a span's end): both halves must carry a
  // share of the error (gauss_kronrod_noise_spread).
  const bool spread = std::min(left.error, right.error) >=
                      tolerances::gauss_kronrod_noise_spread * std::max(left.error, right.error);
  if (depth >= 4 && left.error + right.error > 0.75 * r.error && spread &&
      r.error <= tolerances::gauss_kronrod_noise_relative * r.magnitude) {
    left.ok = left.ok || left.error <= abs_density * (mid - a);
    right.ok = right.ok || right.error <= abs_density * (b - mid);
    accept(a, mid, left);
    accept(mid, b, right);
    return;
  }
  adaptive(curve, a, mid, left, rel_tol, abs_density, depth + 1, evaluations, evaluation_limit, accept);
  adaptive(curve, mid, b, right, rel_tol, abs_density, depth + 1, evaluations, evaluation_limit, accept);
}

// The adaptive integration of one piece between breakpoints.
template <class Accept>
void integrate_piece(const Curve& curve, double a, double b, double rel_tol, long& evaluations, Accept&& accept) {
  const GkResult root = patterson_panel(curve, a, b, rel_tol, evaluations);
  const double abs_density = rel_tol * std::abs(root.value) / (b - a);
  adaptive(curve, a, b, root, rel_tol, abs_density, 0, evaluations,
           evaluations + tolerances::gauss_kronrod_max_piece_evaluations, accept);
}

// Splits [u0, u1] at the curve's breakpoints and calls f(a, b) on each piece.
template <class F>
void for_each_piece(const Curve& curve, double u0, double u1, F&& f) {
  const auto bp = curve.breakpoints();
  double a = u0;
  for (const double x : bp) {
    if (x <= a) continue;
    if (x >= u1) break;
    f(a, x);
    a = x;
  }
  if (u1 > a) f(a, u1);
}

}  // namespace

double fixed_rule_length(const Curve& curve, double a, double b, int level) noexcept {
  const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
  const auto& w = Rules::weights[static_cast<std::size_t>(level)];
  double q = w[0] * curve.speed(centre);
  for (int i = 1; i < Rules::used[static_cast<std::size_t>(level)]; ++i) {
    const double dx = half * Rules::nodes[static_cast<std::size_t>(i)];
    q += w[static_cast<std::size_t>(i)] * (curve.speed(centre - dx) + curve.speed(centre + dx));
  }
  return q * half;
}

LengthResult simpson_runge_length(const Curve& curve, SimpsonScheme scheme, double rel_tol, int max_halvings) {
  LengthResult out;
  out.converged = true;
  auto run = [&](double a, double b, bool record) {
    // Composite Simpson with reuse: ends, sum of odd and of even interior samples.
    // The end b is evaluated as the limit from the left: at a C0 knot the next span's
    // derivative would make the integrand jump and Simpson converge only as O(h).
    const double ends = curve.speed(a) + curve.speed_left(b);
    out.evaluations += 2;
    double even = 0.0;
    double odd = curve.speed(0.5 * (a + b));
    out.evaluations += 1;
    long n = 2;
    double l_prev = (b - a) / 6.0 * (ends + 4.0 * odd);
    if (record) out.history.emplace_back(n, l_prev);
    for (int halving = 1; halving <= max_halvings; ++halving) {
      even += odd;
      odd = 0.0;
      n *= 2;
      const double h = (b - a) / static_cast<double>(n);
      for (long j = 1; j < n; j += 2) odd += curve.speed(a + static_cast<double>(j) * h);
      out.evaluations += n / 2;
      const double l = h / 3.0 * (ends + 4.0 * odd + 2.0 * even);
      if (record) out.history.emplace_back(n, l);
      const double runge = (l - l_prev) / 15.0;
      if (std::abs(runge) < rel_tol * std::abs(l) || l == l_prev) {
        out.length_mm += l + runge;
        out.error_estimate_mm += std::abs(runge);
        return;
      }
      l_prev = l;
    }
    // Not converged within max_halvings: the last corrected value and its estimate.
    const auto& last = l_prev;
    out.length_mm += last;
    out.error_estimate_mm += std::numeric_limits<double>::max() / 1e10;
    out.converged = false;
  };
  if (scheme == SimpsonScheme::whole_curve) {
    run(curve.u_min(), curve.u_max(), true);
  } else {
    for_each_piece(curve, curve.u_min(), curve.u_max(), [&](double a, double b) { run(a, b, false); });
  }
  return out;
}

LengthResult gauss_kronrod_length(const Curve& curve, double u0, double u1, double rel_tol) {
  rel_tol = std::max(rel_tol, tolerances::min_length_relative);
  LengthResult out;
  out.converged = true;
  for_each_piece(curve, u0, u1, [&](double a, double b) {
    integrate_piece(curve, a, b, rel_tol, out.evaluations, [&](double, double, const GkResult& r) {
      out.length_mm += r.value;
      out.error_estimate_mm += r.error;
      out.converged = out.converged && r.ok;
    });
  });
  return out;
}

LengthResult gauss_kronrod_length(const Curve& curve, double rel_tol) {
  return gauss_kronrod_length(curve, curve.u_min(), curve.u_max(), rel_tol);
}

double length(const Curve& curve) { return gauss_kronrod_length(curve).length_mm; }

ArcLengthTable::ArcLengthTable(const Curve& curve, double rel_tol) : curve_(&curve) {
  rel_tol = std::max(rel_tol, tolerances::min_length_relative);
  u_.push_back(curve.u_min());
  s_.push_back(0.0);
  if (const double v = curve.constant_speed(); v > 0.0 && std::isfinite(v)) {
    speed_ = v;
    u_.push_back(curve.u_max());
    s_.push_back(v * (curve.u_max() - curve.u_min()));
    level_.push_back(0);
    return;
  }
  for_each_piece(curve, curve.u_min(), curve.u_max(), [&](double a, double b) {
    integrate_piece(curve, a, b, rel_tol, build_evaluations_, [&](double, double hi, const GkResult& r) {
      u_.push_back(hi);
      s_.push_back(s_.back() + r.value);
      // A part of an interval is integrated with the rule that was accurate on the whole of it.
      level_.push_back(static_cast<unsigned char>(r.level));
    });
  });
}

double ArcLengthTable::s_of_u(double u) const noexcept {
  u = std::clamp(u, u_.front(), u_.back());
  if (u == u_.back()) return s_.back();  // the end: the length itself (no quadrature of the last interval)
  if (speed_ > 0.0) return speed_ * (u - u_.front());
  const auto it = std::upper_bound(u_.begin(), u_.end(), u);
  const std::size_t k = (it == u_.begin()) ? 0 : std::min<std::size_t>(static_cast<std::size_t>(it - u_.begin()) - 1, u_.size() - 2);
  if (u == u_[k]) return s_[k];
  return s_[k] + fixed_rule_length(*curve_, u_[k], u, level_[k]);
}

double ArcLengthTable::u_of_s(double s) const noexcept { return u_of_s(s, std::numeric_limits<double>::quiet_NaN()); }

double ArcLengthTable::u_of_s(double s, double u_hint) const noexcept {
  const double total = s_.back();
  if (!(s > 0.0)) return u_.front();
  if (s >= total) return u_.back();
  if (speed_ > 0.0) return std::min(u_.front() + s / speed_, u_.back());
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(it - s_.begin()) - 1, u_.size() - 2);
  const double ua = u_[k], ub = u_[k + 1], sa = s_[k], sb = s_[k + 1];
  const double ds = s - sa;
  // Initial guess: the cubic Hermite inverse is overkill; the linear one with the end speeds'
  // mean is within a few per cent on a table interval, and Newton does the rest.
  double lo = ua, hi = ub;
  double u = (sb > sa) ? ua + (ub - ua) * (ds / (sb - sa)) : ua;
  if (u_hint > ua && u_hint < ub) u = u_hint;  // false for NaN
  const double ftol = tolerances::inverse_length_relative * std::max(total, 1e-300);
  for (int it_count = 0; it_count < tolerances::inverse_length_max_iterations; ++it_count) {
    const double f = (u > ua ? fixed_rule_length(*curve_, ua, u, level_[k]) : 0.0) - ds;
    if (std::abs(f) <= ftol) break;
    if (f > 0.0) hi = u; else lo = u;
    const double v = curve_->speed(u);
    double next = (v > 0.0) ? u - f / v : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == u || hi - lo <= 4.0 * kEps * std::max(std::abs(lo), std::abs(hi))) {
      u = next;
      break;
    }
    u = next;
  }
  return u;
}

}  // namespace kontur

namespace kontur {

double ArcLengthTable::u_after(double u_from, double s_from, double s_to, double u_hint) const noexcept {
  return u_after(u_from, s_from, s_to, u_hint, 0.0, nullptr);
}

double ArcLengthTable::u_after(double u_from, double s_from, double s_to, double u_hint, double s_from_error,
                               double* s_to_error) const noexcept {
  if (s_to_error != nullptr) *s_to_error = 0.0;
  const double total = s_.back();
  if (s_to >= total) return u_.back();
  if (speed_ > 0.0) return u_of_s(s_to);  // exact (the rounding of u alone)
  const auto it = std::upper_bound(s_.begin(), s_.end(), s_to);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(it - s_.begin()) - 1, u_.size() - 2);
  const double ua = u_[k], ub = u_[k + 1];
  if (!(s_from <= s_to)) return u_of_s(s_to, u_hint);
  if (u_from < ua && s_from <= s_[k] && u_from >= u_.front()) {
    // The step ends in a later table interval: its part there starts at the interval's start,
    // whose arc length the table holds (a shorter step of the same kind).
    u_from = ua;
    s_from = s_[k];
    s_from_error = 0.0;
  }
  if (!(u_from >= ua && u_from < ub)) return u_of_s(s_to, u_hint);
  // (s_to - s_from is exact where both are within a factor of two; the error at u_from is a small
  // number kept apart, so that it is not lost to the rounding of s on a long curve)
  const double ds = (s_to - s_from) - s_from_error;  // [mm]
  if (!(ds > 0.0)) {
    if (s_to_error != nullptr) *s_to_error = -ds;  // already at or past s_to
    return u_from;
  }
  // Newton on F(u) = s_from + length(u_from, u) - s_to, bracketed in [u_from, ub].
  // The residual is asked relative to the step, not to the curve: a residual of 1e-15 of a long
  // curve can be 1e-8 of a 12.5 um step, and it shows as feed fluctuation.
  const double ftol = tolerances::inverse_step_relative * ds;  // [mm]
  double lo = u_from, hi = ub;
  // Initial guess: the third-order Taylor series of u(s) at u_from, from v = |C'|, v' = dv/du and
  // v'' = d2v/du2 [mm per parameter unit^1, ^2, ^3]: du/ds = 1/v, d2u/ds2 = -v'/v^3,
  // d3u/ds3 = (3 v'^2 - v v'')/v^5. Its error is of order (ds/R)^4 of the step, R the length over
  // which the parametric speed changes, so that one Newton step with a second-order correction
  // usually suffices. The caller's hint (or the linear guess) where the series does not apply
  // (v = 0 at a cusp, or a step too long for it).
  double u = std::numeric_limits<double>::quiet_NaN();
  double v_from = 0.0;
  {
    const Derivatives d = curve_->derivatives(u_from, 3);
    const double v = d[1].norm();
    v_from = v;
    if (v > 0.0) {
      const double vp = d[1].dot(d[2]) / v;
      const double vpp = (d[2].dot(d[2]) + d[1].dot(d[3]) - vp * vp) / v;
      const double t1 = ds / v;
      const double t2 = -vp * ds * ds / (2.0 * v * v * v);
      const double t3 = (3.0 * vp * vp - v * vpp) * ds * ds * ds / (6.0 * v * v * v * v * v);
      if (std::abs(t2) <= 0.25 * t1 && std::abs(t3) <= 0.25 * t1) {
        u = u_from + (t1 + t2 + t3);
      }
    }
  }
  if (!(u > lo && u < hi)) {
    u = (u_hint > lo && u_hint < hi) ? u_hint : lo + (hi - lo) * std::min(1.0, ds / std::max(s_[k + 1] - s_from, 1e-300));
  }
  if (!(u > lo && u < hi)) u = 0.5 * (lo + hi);
  for (int i = 0; i < tolerances::inverse_length_max_iterations; ++i) {
    const Derivatives d = curve_->derivatives(u, 2);
    const double v = d[1].norm();
    const double f = step_length(*curve_, u_from, u, v_from, v, 1e-13) - ds;
    if (s_to_error != nullptr) *s_to_error = f;
    if (std::abs(f) <= ftol) break;
    if (f > 0.0) hi = u; else lo = u;
    double next = 0.5 * (lo + hi);
    bool second_order = false;
    if (v > 0.0) {
      // s(u + du) - s_to = f + v du + v' du^2 / 2 + ...: du = -f/v - v' f^2/(2 v^3) + O(f^3).
      const double t1 = f / v;
      const double t2 = d[1].dot(d[2]) * f * f / (2.0 * v * v * v * v);
      second_order = std::abs(t2) <= 0.5 * std::abs(t1);
      next = u - t1 - (second_order ? t2 : 0.0);
    }
    if (next == u) break;
    const bool inside = next > lo && next < hi;
    if (!inside) next = 0.5 * (lo + hi);
    // The error after the step is of order (f/ds)^3 ds with the second-order term, (f/ds)^2 ds
    // without it (times the relative change of the speed over the step, at most of order 1 on a
    // step much shorter than the curve's features): below the thresholds it is far below ftol,
    // so the result needs no further integral.
    const double r = std::abs(f) / ds;
    const bool converged = inside && (r <= tolerances::inverse_step_newton_stop ||
                                      (second_order && r <= tolerances::inverse_step_second_order_stop));
    // The arc length at `next` to first order, with the rounding of `next` itself: on a long curve
    // half an ulp of u times |C'| (5e-11 mm on a 900 m line) is far above ftol, and the same
    // rounding step after step moved the tool 46 nm off its profile over 5.4e6 steps.
    if (s_to_error != nullptr) *s_to_error = v > 0.0 ? f + v * (next - u) : 0.0;
    u = next;
    if (converged || hi - lo <= 4.0 * kEps * std::max(std::abs(lo), std::abs(hi))) break;
  }
  return u;
}

}  // namespace kontur
