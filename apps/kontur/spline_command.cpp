// `kontur spline FILE`: validation, span polynomials (seed 002, upper level), curve length by
// Kontur's Gauss-Kronrod and by the Simpson-Runge method of seed 000 with evaluation counts, and
// with --step the forward-difference table of the lower level.
#include "commands.hpp"

#include <kontur/error.hpp>
#include <kontur/forward_difference.hpp>
#include <kontur/interpolation.hpp>
#include <kontur/io/curve_json.hpp>
#include <kontur/length.hpp>
#include <kontur/span_polynomial.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>

namespace kontur::app {
namespace {

struct SplineOptions {
  std::string file;
  double step = 0.0;
  double tolerance = tolerances::simpson_relative;
  std::string basis = "global";
  std::string summation = "plain";
  double feed_mm_min = 0.0;
  double period_s = 1e-3;
  bool json = false;
};

// Prints a double compactly and exactly enough to read back (shortest round-trip form), with
// negative zero shown as 0.
std::string num(double v) {
  if (v == 0.0) v = 0.0;
  return fmt::format("{}", v);
}

const char* kAxis[4] = {"x", "y", "z", "w"};

void run_spline(const SplineOptions& o) {
  const NurbsCurve curve = read_curve_json(o.file);
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0))
    throw InputError("tolerance-range", fmt::format("--tolerance {}: must be in (0, 1)", o.tolerance));
  if (o.step < 0.0 || !std::isfinite(o.step))
    throw InputError("step-positive", fmt::format("--step {}: must be a finite parameter step > 0", o.step));
  const double range = curve.u_max() - curve.u_min();
  if (o.step > 0.0 && range / o.step > 1e7)
    throw InputError("step-too-small",
                     fmt::format("--step {}: gives {:.0f} rows for the parameter range {}; at most 1e7 are printed",
                                 o.step, range / o.step, range));
  if (o.feed_mm_min < 0.0 || !std::isfinite(o.feed_mm_min))
    throw InputError("feed-positive", fmt::format("--feed {}: must be a finite feed > 0 [mm/min]", o.feed_mm_min));
  if (!(o.period_s > 0.0 && o.period_s <= 1.0))
    throw InputError("period-range", fmt::format("--period {}: must be in (0, 1] [s]", o.period_s));
  const bool global = o.basis == "global";
  const SpanPolynomialCurve spans(curve);
  const int p = curve.degree();
  const int dims = curve.rational() ? 4 : 3;
  const LengthResult gk = gauss_kronrod_length(spans, std::min(o.tolerance, tolerances::length_relative));
  const LengthResult s1 = simpson_runge_length(spans, SimpsonScheme::per_span, o.tolerance);
  const LengthResult s2 = simpson_runge_length(spans, SimpsonScheme::whole_curve, o.tolerance);
  const Summation summation = o.summation == "compensated" ? Summation::compensated : Summation::plain;
  // Seed 004: feed fluctuation of the interpolators at the constant feed --feed.
  struct Fluct {
    Interpolator kind;
    FeedFluctuation f;
  };
  std::vector<Fluct> fluct;
  if (o.feed_mm_min > 0.0) {
    const double cycles = gk.length_mm / (o.feed_mm_min / 60.0 * o.period_s);
    if (cycles > 1e7)
      throw InputError("too-many-cycles", fmt::format("--feed {} --period {}: {:.0f} cycles along {:.3f} mm; at most "
                                                      "1e7 are measured",
                                                      o.feed_mm_min, o.period_s, cycles, gk.length_mm));
    for (const Interpolator k :
         {Interpolator::taylor_first_order, Interpolator::taylor_second_order, Interpolator::arc_length_exact})
      fluct.push_back({k, measure_feed_fluctuation(spans, k, o.feed_mm_min / 60.0, o.period_s)});
  }

  if (o.json) {
    nlohmann::ordered_json j;
    j["file"] = o.file;
    j["valid"] = true;
    j["degree"] = p;
    j["control_points"] = curve.points().size();
    j["knots"] = curve.knots().size();
    j["rational"] = curve.rational();
    j["u_range"] = {curve.u_min(), curve.u_max()};
    j["basis"] = global ? "global: coefficients of u^k" : "local: coefficients of (u - u_start)^k";
    auto& js = j["spans"] = nlohmann::ordered_json::array();
    for (const auto& s : spans.spans()) {
      nlohmann::ordered_json e;
      e["u_start"] = s.u_start;
      e["u_end"] = s.u_end;
      for (int a = 0; a < dims; ++a) {
        const PolyCoeffs c = s.coefficients(a, global ? 0.0 : s.u_start);
        std::vector<double> v(c.begin(), c.begin() + p + 1);
        e["coefficients"][kAxis[a]] = v;  // ascending powers
      }
      js.push_back(e);
    }
    auto length_json = [](const LengthResult& r) {
      nlohmann::ordered_json e;
      e["length_mm"] = r.length_mm;
      e["error_estimate_mm"] = r.error_estimate_mm;
      e["evaluations"] = r.evaluations;
      e["converged"] = r.converged;
      if (!r.history.empty()) {
        auto& h = e["history"] = nlohmann::ordered_json::array();
        for (const auto& [n, l] : r.history) h.push_back({{"n", n}, {"length_mm", l}});
      }
      return e;
    };
    j["length"]["gauss_kronrod"] = length_json(gk);
    j["length"]["simpson_runge_per_span"] = length_json(s1);
    j["length"]["simpson_runge_whole_curve"] = length_json(s2);
    if (!fluct.empty()) {
      auto& jf = j["feed_fluctuation"];
      jf["feed_mm_min"] = o.feed_mm_min;
      jf["period_s"] = o.period_s;
      for (const auto& f : fluct) {
        jf[to_string(f.kind)] = {{"cycles", f.f.cycles},
                                 {"max_relative", f.f.max_relative},
                                 {"mean_relative", f.f.mean_relative},
                                 {"max_chord_error_mm", f.f.max_chord_error_mm}};
      }
    }
    if (o.step > 0.0) {
      ForwardDifferenceStepper fd(spans, o.step, summation);
      auto& rows = j["forward_differences"]["rows"] = nlohmann::ordered_json::array();
      j["forward_differences"]["h"] = o.step;
      do {
        nlohmann::ordered_json r;
        r["n"] = fd.n();
        r["u"] = fd.u();
        r["span"] = fd.span();
        const Vec3 q = fd.point();
        r["point"] = {q.x(), q.y(), q.z()};
        for (int a = 0; a < dims; ++a) {
          const auto d = fd.differences(a);
          r["differences"][kAxis[a]] = std::vector<double>(d.begin(), d.begin() + fd.degree() + 1);
        }
        rows.push_back(r);
      } while (fd.step());
    }
    fmt::print("{}\n", j.dump(2));
    return;
  }

  fmt::print("curve       {}\n", o.file);
  fmt::print("valid       {} of degree {}, {} control points, {} knots, {} span{}, u in [{}, {}]\n",
             curve.rational() ? "NURBS (rational)" : "B-spline (non-rational)", p, curve.points().size(),
             curve.knots().size(), spans.spans().size(), spans.spans().size() == 1 ? "" : "s", num(curve.u_min()),
             num(curve.u_max()));
  fmt::print("\nspan polynomials (upper level), {}; coefficients from the highest power down{}\n",
             global ? "power basis in u" : "power basis in t = u - u_start",
             curve.rational() ? "; homogeneous (w x, w y, w z, w)" : "");
  for (std::size_t i = 0; i < spans.spans().size(); ++i) {
    const auto& s = spans.spans()[i];
    fmt::print("  span {} [{}, {}):\n", i, num(s.u_start), num(s.u_end));
    for (int a = 0; a < dims; ++a) {
      const PolyCoeffs c = s.coefficients(a, global ? 0.0 : s.u_start);
      std::string line;
      for (int k = p; k >= 0; --k) line += fmt::format(" {:>22}", num(c[static_cast<std::size_t>(k)]));
      fmt::print("    {}{}\n", kAxis[a], line);
    }
  }
  fmt::print("\nlength [mm]                      length      error estimate    evaluations of |C'(u)|\n");
  auto row = [](const char* name, const LengthResult& r) {
    fmt::print("  {:<28} {:>18.12f} {:>14.3g} {:>14}{}\n", name, r.length_mm, r.error_estimate_mm, r.evaluations,
               r.converged ? "" : "  (not converged)");
  };
  row("Gauss-Kronrod (default)", gk);
  row("Simpson-Runge per span", s1);
  row("Simpson-Runge whole curve", s2);
  fmt::print("  Simpson whole-curve table (seed 000): n, l_n [mm]\n");
  for (const auto& [n, l] : s2.history) fmt::print("    {:>8} {:>18.6f}\n", n, l);

  if (!fluct.empty()) {
    fmt::print("\nfeed fluctuation (seed 004) at F = {} mm/min, T = {} s: |arc of a cycle / (F T) - 1|\n", num(o.feed_mm_min),
               num(o.period_s));
    fmt::print("  {:<10} {:>10} {:>14} {:>14} {:>18}\n", "interp.", "cycles", "max", "mean", "max chord err [mm]");
    for (const auto& f : fluct)
      fmt::print("  {:<10} {:>10} {:>14.3e} {:>14.3e} {:>18.3e}\n", to_string(f.kind), f.f.cycles, f.f.max_relative,
                 f.f.mean_relative, f.f.max_chord_error_mm);
  }

  if (o.step > 0.0) {
    ForwardDifferenceStepper fd(spans, o.step, summation);
    fmt::print("\nforward differences (lower level), h = {}, {} summation, {} cycles\n", num(o.step), o.summation,
               fd.cycles() + 1);
    std::string head = fmt::format("  {:>8} {:>12} {:>4}", "n", "u", "span");
    for (int a = 0; a < dims; ++a)
      for (int k = 0; k <= p; ++k) head += fmt::format(" {:>14}", k == 0 ? std::string(kAxis[a]) : fmt::format("D{}{}", k, kAxis[a]));
    fmt::print("{}\n", head);
    do {
      std::string line = fmt::format("  {:>8} {:>12.8g} {:>4}", fd.n(), fd.u(), fd.span());
      for (int a = 0; a < dims; ++a)
        for (int k = 0; k <= fd.degree(); ++k) {
          const double d = fd.differences(a)[static_cast<std::size_t>(k)];
          line += fmt::format(" {:>14.8g}", d == 0.0 ? 0.0 : d);
        }
      fmt::print("{}\n", line);
    } while (fd.step());
  }
}

}  // namespace

void register_spline_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<SplineOptions>();
  CLI::App* cmd = app.add_subcommand(
      "spline", "Validate a NURBS curve file (JSON), print its span polynomials, its length by Gauss-Kronrod and "
                "by Simpson-Runge with their evaluation counts, and with --step the forward-difference table.");
  cmd->add_option("FILE", opts->file, "curve file: {\"degree\": 3, \"knots\": [...], \"points\": [[x,y,z],...], "
                                      "\"weights\": [...]}")
      ->required();
  cmd->add_option("--step", opts->step, "parameter step h per cycle for the forward-difference table");
  cmd->add_option("--tolerance", opts->tolerance, "relative tolerance of the Simpson-Runge length")
      ->capture_default_str();
  cmd->add_option("--basis", opts->basis, "polynomial variable: global (u, as the seed's Table 2) or local (u - u_start)")
      ->check(CLI::IsMember({"global", "local"}))
      ->capture_default_str();
  cmd->add_option("--summation", opts->summation, "forward-difference additions: plain or compensated")
      ->check(CLI::IsMember({"plain", "compensated"}))
      ->capture_default_str();
  cmd->add_option("--feed", opts->feed_mm_min,
                  "constant feed F [mm/min]: measure the feed fluctuation of the Taylor interpolators (seed 004) and "
                  "of Kontur's arc-length-exact one");
  cmd->add_option("--period", opts->period_s, "servo period T [s] for --feed")->capture_default_str();
  cmd->add_flag("--json", opts->json, "print the result as JSON");
  cmd->footer("Examples:\n  kontur spline examples/curves/seed_example1.json --step 0.05\n"
              "  kontur spline examples/curves/seed_example2.json --feed 6000 --period 0.001\n"
              "Exit codes: 0 valid curve, 1 invalid curve or file, 2 wrong command line.");
  cmd->callback([opts, &exit_code]() {
    run_spline(*opts);
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
