// The upper level of the segment stream (segments/segment_stream.hpp, docs/segments.md).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <kontur/error.hpp>
#include <kontur/segments/segment_stream.hpp>

#include "kontur_ll.h"
#include "segment_bytes.hpp"

namespace kontur::segments {
namespace {

constexpr int kChannels = KLL_MAX_CHANNELS;
constexpr int kDegree = KLL_MAX_DEGREE;
using Coeffs = std::array<double, kDegree + 1>;

// Forward differences at m = 0 of m^j, orders k = 0..5: k! S(j, k) (S: Stirling numbers of the
// second kind). Row j converts a power-basis coefficient to Newton's forward form.
constexpr std::array<Coeffs, kDegree + 1> kPowerToNewton = {{
    {1, 0, 0, 0, 0, 0},
    {0, 1, 0, 0, 0, 0},
    {0, 1, 2, 0, 0, 0},
    {0, 1, 6, 6, 0, 0},
    {0, 1, 14, 36, 24, 0},
    {0, 1, 30, 150, 240, 120},
}};
// One setpoint in the writer's units: per channel (the axes, then the path speed) the value, its
// first and second derivative per servo cycle (velocity * T, acceleration * T^2).
struct Sample {
  std::array<double, kChannels> x{}, v{}, a{};
  long line = 0;
  // Per axis, the largest backward difference of order 1, 2, 3 a replayed setpoint here may have
  // [mm] ([deg]): the limit times T^k, or the planner's own difference where it is larger;
  // `orders` of them apply (fewer at the start).
  std::array<std::array<double, 3>, kChannels> allowed{};
  int orders = 0;
};

// Value and first two derivatives of a power-basis polynomial at m.
struct Jet {
  double value = 0.0, d1 = 0.0, d2 = 0.0;
};
Jet evaluate(const Coeffs& c, double m) {
  Jet j;
  for (int k = kDegree; k >= 0; --k) {
    j.d2 = j.d2 * m + 2.0 * j.d1;
    j.d1 = j.d1 * m + j.value;
    j.value = j.value * m + c[static_cast<std::size_t>(k)];
  }
  return j;
}

// A piece's encoding.
struct Encoding {
  int degree = kDegree;
  bool f32 = false;
};

}  // namespace

struct SegmentWriter::Impl {
  // How far replayed channel values are from a sample (deviation()).
  struct Deviation {
    double ratio = 0.0;       // the largest, in tolerances (what a piece must keep <= 1)
    double tool_mm = 0.0;     // the tool point's distance [mm]
    double extra = 0.0;       // the largest extra axis difference [mm] or [deg]
    double speed_mm_s = 0.0;  // the path speed's [mm/s]
  };
  std::ostream* out = nullptr;
  double period_s = 0.0;
  int axes = 3, channels = 4;
  SegmentOptions options;
  std::array<double, kChannels> tolerance{};  // per channel [mm] / [mm/s]
  std::deque<Sample> held;                    // setpoints not yet in a piece
  kll_stream state{};                         // the lower level after every record written
  std::uint32_t index = 0;                    // index of the next record
  bool finished = false;
  // The candidate piece: anchor or continuation, and its coefficients per channel (anchor: power
  // basis c0..c5 in the cycle index; continuation: the changes dc3..dc5 in coefficients 3..5).
  bool anchor = false;
  std::array<Coeffs, kChannels> coeffs{};
  std::array<Coeffs, kChannels> base{};  // the state's polynomial (power basis) at the piece's start
  std::vector<std::uint8_t> record;
  kll_stream trial{};
  // The last three replayed setpoints before the held ones, newest first (the backward
  // differences of the limit check), and the planner's last three setpoints written (for the
  // allowed differences of each new sample); how many of each are known.
  std::array<std::array<double, kChannels>, 3> replayed_before{}, planned_last{};
  int planned_known = 0;
  bool bounded = false;
  bool enforce_limits = true;
  int last_length = 1;  // cycles of the last piece: where the search for the next starts
  // Setpoints are numbered from 0 in the order written: held[0] is setpoint `held_first`. The
  // numbers of the setpoints where the machine comes to rest or leaves it (a piece ends there)
  // and of those whose line differs from the one before (a mark), not yet in a piece.
  long held_first = 0;
  std::deque<long> rest_edges, line_changes;
  bool previous_rest = false;
  // The candidate's replayed positions, newest first: [0] the setpoint being checked.
  std::array<std::array<double, kChannels>, 4> replay_window{};
  // What the last passing check() saw, for the commit: the largest deviations of its setpoints
  // and its last three replayed setpoints (newest first).
  Deviation trial_worst;
  std::array<std::array<double, kChannels>, 3> trial_before{};

  void write_header(SegmentStats& stats, const AxisLayout& layout);
  void fit_piece(SegmentStats& stats);
  [[nodiscard]] bool needs_anchor() const;
  [[nodiscard]] bool at_rest(const Sample& s) const;
  void solve(int n);
  void encode(int n, Encoding e);
  [[nodiscard]] double check(int n);
  [[nodiscard]] Deviation deviation(const double* r, const Sample& s) const;
  // Whether the replayed setpoint `r` (the m-th of the candidate, m = 0..n) keeps the limits where
  // the planner's does.
  [[nodiscard]] bool keeps_limits(int m, const double* r);
  [[nodiscard]] bool fits(int n) {
    solve(n);
    encode(n, {});
    return check(n) <= 1.0;
  }
};

SegmentWriter::SegmentWriter(std::ostream& out, double period_s, const AxisLayout& layout, SegmentOptions options)
    : impl_(std::make_unique<Impl>()) {
  if (!std::isfinite(options.tolerance_mm) || options.tolerance_mm < tolerances::segment_min_tolerance_mm)
    throw InputError("segment-tolerance",
                     fmt::format("the segment tolerance {} mm is below the smallest the lower level's rounding allows "
                                 "({} mm)",
                                 options.tolerance_mm, tolerances::segment_min_tolerance_mm));
  if (options.max_piece_cycles < 1 || options.max_piece_cycles > 65535)
    throw InputError("segment-piece", fmt::format("the longest piece must be 1 to 65535 cycles, not {}",
                                                  options.max_piece_cycles));
  if (!(period_s > 0.0) || !std::isfinite(period_s))
    throw InputError("segment-period", fmt::format("the servo period {} s is not positive", period_s));
  Impl& m = *impl_;
  m.out = &out;
  m.period_s = period_s;
  m.axes = layout.size();
  m.channels = m.axes + 1;
  m.options = options;
  // The fit keeps a share of the tolerance: the planner's own setpoints lie up to ~1e-14 mm off
  // the path, and the sum must stay within the tolerance a check of the replay applies.
  const double fit_mm = options.tolerance_mm * tolerances::segment_tolerance_share;
  for (int c = 0; c < m.axes; ++c) m.tolerance[static_cast<std::size_t>(c)] = fit_mm;
  m.bounded = !options.bounds.empty();
  if (m.bounded && static_cast<int>(options.bounds.size()) != m.axes)
    throw std::invalid_argument("SegmentWriter: one AxisBounds per axis of the layout");
  m.tolerance[static_cast<std::size_t>(m.axes)] = fit_mm / period_s;
  m.write_header(stats_, layout);
}

SegmentWriter::~SegmentWriter() = default;

void SegmentWriter::Impl::write_header(SegmentStats& stats, const AxisLayout& layout) {
  std::array<std::uint8_t, KLL_HEADER_SIZE> h{};
  std::memcpy(h.data(), segment_stream_magic, 8);
  bytes::put_u32(h.data() + 8, KLL_FORMAT_VERSION);
  bytes::put_u32(h.data() + 12, static_cast<std::uint32_t>(axes));
  for (int i = 0; i < axes; ++i) h[16 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(layout.letter(i));
  bytes::put_f64(h.data() + 32, period_s);
  bytes::put_f64(h.data() + 40, options.tolerance_mm);
  bytes::put_f64(h.data() + 48, options.tolerance_mm / period_s);
  bytes::put_u32(h.data() + 60, kll_crc32(h.data(), 60));
  if (kll_open(&state, h.data(), h.size()) != KLL_OK)
    throw InputError("segment-header", "the segment stream's header cannot be read back (an axis count or period out of range)");
  out->write(reinterpret_cast<const char*>(h.data()), static_cast<std::streamsize>(h.size()));
  stats.bytes += h.size();
}

void SegmentWriter::write(const trajectory::Setpoint& s) {
  Impl& m = *impl_;
  Sample x;
  const double t = m.period_s;
  for (int c = 0; c < m.axes; ++c) {
    const auto i = static_cast<std::size_t>(c);
    x.x[i] = s.position[c];
    x.v[i] = s.velocity.size() > c ? s.velocity[c] * t : 0.0;
    x.a[i] = s.acceleration.size() > c ? s.acceleration[c] * t * t : 0.0;
  }
  const auto sp = static_cast<std::size_t>(m.axes);
  x.x[sp] = s.v_mm_s;
  x.v[sp] = s.a_mm_s2 * t;
  x.a[sp] = s.j_mm_s3 * t * t;
  x.line = s.source_line;
  if (m.bounded) {
    // What a replayed setpoint here may do: the limits, or the planner's own differences.
    x.orders = std::min(m.planned_known, 3);
    const auto& p1 = m.planned_last[0];
    const auto& p2 = m.planned_last[1];
    const auto& p3 = m.planned_last[2];
    for (int c = 0; c < m.axes; ++c) {
      const auto i = static_cast<std::size_t>(c);
      const AxisBounds& b = m.options.bounds[i];
      const double d[3] = {x.x[i] - p1[i], x.x[i] - 2 * p1[i] + p2[i], x.x[i] - 3 * p1[i] + 3 * p2[i] - p3[i]};
      const double limit[3] = {b.max_velocity * t, b.max_acceleration * t * t, b.max_jerk * t * t * t};
      for (std::size_t k = 0; k < 3; ++k) x.allowed[i][k] = std::max(limit[k], std::abs(d[k]));
    }
    m.planned_last[2] = m.planned_last[1];
    m.planned_last[1] = m.planned_last[0];
    m.planned_last[0] = x.x;
    ++m.planned_known;
  }
  // Where pieces must end (rest edges) and where marks go (line changes), by setpoint number.
  const long number = m.held_first + static_cast<long>(m.held.size());
  const bool rest = m.at_rest(x);
  if (number > 0) {
    if (x.line != m.held.back().line) m.line_changes.push_back(number);
    if (m.previous_rest && !rest && (m.rest_edges.empty() || m.rest_edges.back() != number - 1))
      m.rest_edges.push_back(number - 1);  // leaves rest
    if (rest && !m.previous_rest) m.rest_edges.push_back(number);  // comes to rest
  }
  m.previous_rest = rest;
  m.held.push_back(x);
  ++stats_.setpoints;
  // A piece needs the setpoint after its last (its end conditions): fit once the longest fits.
  while (m.held.size() > static_cast<std::size_t>(m.options.max_piece_cycles)) m.fit_piece(stats_);
}

void SegmentWriter::finish() {
  Impl& m = *impl_;
  if (m.finished) return;
  m.finished = true;
  if (!m.held.empty()) {
    // The run ends at rest: the last setpoint held once more is the last piece's end condition.
    Sample last = m.held.back();
    for (int c = 0; c < m.channels; ++c) last.v[static_cast<std::size_t>(c)] = last.a[static_cast<std::size_t>(c)] = 0.0;
    m.held.push_back(last);
    while (m.held.size() > 1) m.fit_piece(stats_);
    m.held.clear();
  }
  // The end record: the number of setpoints.
  m.record.assign(KLL_RECORD_HEAD_SIZE + 8 + 4, 0);
  m.record[0] = KLL_KIND_END;
  bytes::put_u16(m.record.data() + 6, static_cast<std::uint16_t>(m.index & 0xffffu));
  bytes::put_u16(m.record.data() + 8, static_cast<std::uint16_t>(m.record.size()));
  bytes::put_u64(m.record.data() + KLL_RECORD_HEAD_SIZE, static_cast<std::uint64_t>(stats_.setpoints));
  bytes::put_u32(m.record.data() + KLL_RECORD_HEAD_SIZE + 8, kll_crc32(m.record.data(), KLL_RECORD_HEAD_SIZE + 8));
  m.out->write(reinterpret_cast<const char*>(m.record.data()), static_cast<std::streamsize>(m.record.size()));
  stats_.bytes += m.record.size();
  ++m.index;
}

bool SegmentWriter::Impl::at_rest(const Sample& s) const {
  for (int c = 0; c < channels; ++c) {
    const auto i = static_cast<std::size_t>(c);
    if (s.v[i] != 0.0 || s.a[i] != 0.0) return false;
  }
  return s.x[static_cast<std::size_t>(axes)] == 0.0;
}

bool SegmentWriter::Impl::needs_anchor() const {
  if (index == 0) return true;
  // At rest (a stop at a block end, a dwell): exactly where the planner is, so stops are exact.
  const Sample& s = held.front();
  if (!at_rest(s)) return false;
  for (int c = 0; c < channels; ++c) {
    const auto i = static_cast<std::size_t>(c);
    if (state.d[i][0] != s.x[i]) return true;
    for (int k = 1; k <= kDegree; ++k)
      if (state.d[i][static_cast<std::size_t>(k)] != 0.0) return true;
  }
  return false;
}

// The quintic Hermite correction over n cycles: from the base polynomial (the state's, or for an
// anchor the exact position, velocity and acceleration of the first setpoint), the coefficients
// 3..5 that reach setpoint n's position, velocity and acceleration.
void SegmentWriter::Impl::solve(int n) {
  const Sample& end = held[static_cast<std::size_t>(n)];
  const double nd = static_cast<double>(n);
  for (int c = 0; c < channels; ++c) {
    const auto i = static_cast<std::size_t>(c);
    const Jet b = evaluate(base[i], nd);
    const double ra = end.x[i] - b.value, rb = nd * (end.v[i] - b.d1), rc = nd * nd * (end.a[i] - b.d2);
    const double e3 = 10.0 * ra - 4.0 * rb + 0.5 * rc;
    const double e4 = -15.0 * ra + 7.0 * rb - rc;
    const double e5 = 6.0 * ra - 3.0 * rb + 0.5 * rc;
    // Corrections far below the tolerance (a channel that does not move, a cubic stretch) are
    // none: no values of 1e-40 in an axis that stands still.
    const double negligible = 1e-6 * tolerance[i];
    const bool none = std::abs(e3) <= negligible && std::abs(e4) <= negligible && std::abs(e5) <= negligible;
    Coeffs& k = coeffs[i];
    if (anchor) {
      k = base[i];
    } else {
      k.fill(0.0);
    }
    if (none) continue;
    k[3] += e3 / (nd * nd * nd);
    k[4] += e4 / (nd * nd * nd * nd);
    k[5] += e5 / (nd * nd * nd * nd * nd);
  }
}

void SegmentWriter::Impl::encode(int n, Encoding e) {
  record.assign(KLL_RECORD_HEAD_SIZE, 0);
  record[0] = static_cast<std::uint8_t>(anchor ? KLL_KIND_ANCHOR : KLL_KIND_CONTINUE);
  record[1] = static_cast<std::uint8_t>(e.degree);
  bytes::put_u16(record.data() + 4, static_cast<std::uint16_t>(n));
  bytes::put_u16(record.data() + 6, static_cast<std::uint16_t>(index & 0xffffu));
  std::uint8_t flags = e.f32 ? KLL_FLAG_FLOAT32 : 0u;
  // The line of the first setpoint, when it is not the one the lower level already has.
  if (index == 0 || held.front().line != state.line) {
    flags |= KLL_FLAG_LINE;
    record.resize(record.size() + 4);
    bytes::put_u32(record.data() + KLL_RECORD_HEAD_SIZE, static_cast<std::uint32_t>(static_cast<std::int32_t>(held.front().line)));
  }
  record[2] = flags;
  // The line changes inside the piece: offset step and line step, as varints.
  int marks = 0, previous = 0;
  for (int m = 1; m < n; ++m) {
    const long line = held[static_cast<std::size_t>(m)].line, before = held[static_cast<std::size_t>(m - 1)].line;
    if (line == before) continue;
    bytes::put_varint(record, static_cast<std::uint32_t>(m - previous));
    const auto step = static_cast<std::int32_t>(static_cast<std::uint32_t>(line) - static_cast<std::uint32_t>(before));
    bytes::put_varint(record, (static_cast<std::uint32_t>(step) << 1) ^ static_cast<std::uint32_t>(step >> 31));
    previous = m;
    ++marks;
  }
  record[3] = static_cast<std::uint8_t>(marks);
  auto put = [&](double v) {
    const std::size_t at = record.size();
    if (e.f32) {
      record.resize(at + 4);
      bytes::put_f32(record.data() + at, static_cast<float>(v));
    } else {
      record.resize(at + 8);
      bytes::put_f64(record.data() + at, v);
    }
  };
  std::uint32_t mask = 0;
  for (int c = 0; c < channels; ++c) {
    const Coeffs& k = coeffs[static_cast<std::size_t>(c)];
    if (anchor) {
      // Newton's forward form of the polynomial cut to the degree: D_0 = c_0 exactly.
      mask |= 1u << c;
      for (int d = 0; d <= e.degree; ++d) {
        double v = 0.0;
        for (int j = d; j <= e.degree; ++j)
          v += kPowerToNewton[static_cast<std::size_t>(j)][static_cast<std::size_t>(d)] * k[static_cast<std::size_t>(j)];
        put(d == 0 ? k[0] : v);
      }
    } else {
      // A channel whose coefficients do not change carries no values.
      bool changes = false;
      for (int j = 3; j <= e.degree; ++j) changes = changes || k[static_cast<std::size_t>(j)] != 0.0;
      if (!changes) continue;
      mask |= 1u << c;
      for (int j = 3; j <= e.degree; ++j) put(k[static_cast<std::size_t>(j)]);
    }
  }
  bytes::put_u16(record.data() + 10, static_cast<std::uint16_t>(mask));
  bytes::put_u16(record.data() + 8, static_cast<std::uint16_t>(record.size() + 4));
  const std::size_t at = record.size();
  record.resize(at + 4);
  bytes::put_u32(record.data() + at, kll_crc32(record.data(), at));
}

SegmentWriter::Impl::Deviation SegmentWriter::Impl::deviation(const double* r, const Sample& s) const {
  // The tool point X Y Z together (the layout starts with them), every other channel alone.
  Deviation d;
  double tool = 0.0, along = 0.0, speed2 = 0.0;
  for (int c = 0; c < 3 && c < axes; ++c) {
    const auto i = static_cast<std::size_t>(c);
    const double e = r[i] - s.x[i];
    tool += e * e;
    along += e * s.v[i];
    speed2 += s.v[i] * s.v[i];
  }
  d.tool_mm = std::sqrt(tool);
  d.ratio = d.tool_mm / tolerance[0];
  // A replayed tool point off along the path by dt cycles is where the planner's was dt cycles
  // later: an extra axis must be off by its own velocity times dt, or a check that places the
  // extra axes from the tool point's distance along the move sees the difference. Both errors
  // count.
  const double dt = speed2 > 0.0 ? along / speed2 : 0.0;
  for (int c = 3; c < axes; ++c) {
    const auto i = static_cast<std::size_t>(c);
    const double e = r[i] - s.x[i];
    d.extra = std::max(d.extra, std::abs(e));
    d.ratio = std::max({d.ratio, std::abs(e) / tolerance[i], std::abs(e - s.v[i] * dt) / tolerance[i]});
  }
  const auto sp = static_cast<std::size_t>(axes);
  d.speed_mm_s = std::abs(r[sp] - s.x[sp]);
  d.ratio = std::max(d.ratio, d.speed_mm_s / tolerance[sp]);
  return d;
}

bool SegmentWriter::Impl::keeps_limits(int m, const double* r) {
  for (int k = 3; k > 0; --k) replay_window[static_cast<std::size_t>(k)] = replay_window[static_cast<std::size_t>(k - 1)];
  std::array<double, kChannels>& w0 = replay_window[0];
  for (int c = 0; c < axes; ++c) w0[static_cast<std::size_t>(c)] = r[c];
  const Sample& s = held[static_cast<std::size_t>(m)];
  const auto& w1 = replay_window[1];
  const auto& w2 = replay_window[2];
  const auto& w3 = replay_window[3];
  for (int c = 0; c < axes; ++c) {
    const auto i = static_cast<std::size_t>(c);
    const auto& allowed = s.allowed[i];
    if (s.orders >= 1 && std::abs(w0[i] - w1[i]) > allowed[0]) return false;
    if (s.orders >= 2 && std::abs(w0[i] - 2 * w1[i] + w2[i]) > allowed[1]) return false;
    if (s.orders >= 3 && std::abs(w0[i] - 3 * w1[i] + 3 * w2[i] - w3[i]) > allowed[2]) return false;
  }
  return true;
}

// Runs the lower level on the encoded record: the largest distance of its setpoints 0..n (n: the
// next piece's first, which this piece's end state decides) from the planner's, in tolerances;
// infinity if one is beyond the tolerance or breaks a limit the planner's keeps.
double SegmentWriter::Impl::check(int n) {
  trial = state;
  if (kll_feed(&trial, record.data(), record.size()) != KLL_OK) return INFINITY;
  if (bounded)
    for (int k = 0; k < 3; ++k)  // (keeps_limits shifts them by one before it adds setpoint m)
      replay_window[static_cast<std::size_t>(k)] = replayed_before[static_cast<std::size_t>(k)];
  kll_setpoint sp;
  std::array<double, kChannels> r{};
  double worst = 0.0;
  Deviation worst_setpoint;
  std::array<std::array<double, kChannels>, 3> last3 = replayed_before;
  for (int m = 0; m <= n; ++m) {
    if (m < n) {
      kll_next(&trial, &sp);
      for (int c = 0; c < axes; ++c) r[static_cast<std::size_t>(c)] = sp.position[static_cast<std::size_t>(c)];
      r[static_cast<std::size_t>(axes)] = sp.speed_mm_s;
    } else {  // the next piece's first setpoint: where this one leaves the state
      for (int c = 0; c < channels; ++c) r[static_cast<std::size_t>(c)] = trial.d[static_cast<std::size_t>(c)][0];
    }
    const Deviation d = deviation(r.data(), held[static_cast<std::size_t>(m)]);
    // The state a piece leaves is where the next one starts: it must be the planner's to a
    // thousandth of the tolerance, or the next piece would have to bend back (a bump in the
    // acceleration and jerk the replayed setpoints show).
    if (!(d.ratio <= (m < n ? 1.0 : tolerances::segment_end_share))) return INFINITY;
    worst = std::max(worst, d.ratio);
    if (bounded && enforce_limits && !keeps_limits(m, r.data())) return INFINITY;
    if (m < n) {
      worst_setpoint.tool_mm = std::max(worst_setpoint.tool_mm, d.tool_mm);
      worst_setpoint.extra = std::max(worst_setpoint.extra, d.extra);
      worst_setpoint.speed_mm_s = std::max(worst_setpoint.speed_mm_s, d.speed_mm_s);
      // The replayed setpoints the next piece's limit check reaches back to.
      last3[2] = last3[1];
      last3[1] = last3[0];
      last3[0] = r;
    }
  }
  trial_worst = worst_setpoint;
  trial_before = last3;
  // The next piece's first backward differences reach back into this one: they must keep the
  // limits even if it makes the planner's setpoints exactly (as its shortest piece does).
  if (bounded && enforce_limits)
    for (int m = n + 1; m <= n + 3 && m < static_cast<int>(held.size()); ++m)
      if (!keeps_limits(m, held[static_cast<std::size_t>(m)].x.data())) return INFINITY;
  return worst;
}

void SegmentWriter::Impl::fit_piece(SegmentStats& stats) {
  // The longest piece the setpoints held and the marks allow.
  int limit = static_cast<int>(std::min<std::size_t>(held.size() - 1, static_cast<std::size_t>(options.max_piece_cycles)));
  while (!line_changes.empty() && line_changes.front() <= held_first) line_changes.pop_front();
  while (!rest_edges.empty() && rest_edges.front() <= held_first) rest_edges.pop_front();
  // At most KLL_MAX_MARKS line changes inside the piece: it ends before the next one.
  if (line_changes.size() > static_cast<std::size_t>(KLL_MAX_MARKS))
    limit = std::min(limit, static_cast<int>(line_changes[KLL_MAX_MARKS] - held_first));
  // Stops are exact: a piece ends where the machine comes to rest and where it leaves rest, so
  // that a rest is one anchor of degree 0 holding the planner's position.
  if (!rest_edges.empty()) limit = std::min(limit, static_cast<int>(rest_edges.front() - held_first));
  anchor = needs_anchor();
  auto set_base = [&] {
    const Sample& s = held.front();
    for (int c = 0; c < channels; ++c) {
      const auto i = static_cast<std::size_t>(c);
      Coeffs& b = base[i];
      b.fill(0.0);
      if (anchor) {
        b[0] = s.x[i];
        b[1] = s.v[i];
        b[2] = 0.5 * s.a[i];
      } else {
        for (int k = 0; k <= kDegree; ++k)
          for (int j = 0; j <= k; ++j)
            b[static_cast<std::size_t>(j)] += state.d[i][static_cast<std::size_t>(k)] *
                                              newton_to_power[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
      }
    }
  };
  set_base();
  if (!fits(1) && !anchor) {
    // The carried state cannot go on within the tolerance (or the limits): start afresh from the
    // planner's exact state (an anchor's first setpoint is the planner's).
    anchor = true;
    set_base();
  }
  int lo = 1;
  if (fits(1)) {
    // The longest piece within the tolerance: from the last piece's length (neighbouring pieces
    // are alike), doubling up or halving down, then bisection.
    int hi = limit + 1;  // the shortest length known not to fit (or past the limit)
    int guess = std::clamp(last_length, 1, limit);
    if (guess > 1 && !fits(guess)) {
      hi = guess;
      for (guess /= 2; guess > 1 && !fits(guess); guess /= 2) hi = guess;
    }
    lo = std::max(guess, 1);
    while (2 * lo < hi && fits(2 * lo)) lo *= 2;
    hi = std::min(hi, 2 * lo);
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (fits(mid) ? lo : hi) = mid;
    }
  } else {
    // Not even one cycle keeps the limits: the planner's exact setpoints, one cycle (its
    // backward differences then differ from the planner's by the rounding of the last pieces).
    enforce_limits = false;
    const bool exact = fits(1);
    enforce_limits = true;
    if (!exact)
      throw InputError("segment-tolerance",
                       fmt::format("the segment tolerance {} mm is below what the lower level's arithmetic reaches at "
                                   "setpoint {}: give a larger --segment-tolerance",
                                   options.tolerance_mm, stats.setpoints - static_cast<long>(held.size())));
    ++stats.limit_fallbacks;
  }
  const int n = lo;
  last_length = n;
  solve(n);
  // The fewest bytes that still fit.
  static constexpr std::array<Encoding, 5> continuations = {{{2, false}, {3, true}, {3, false}, {5, true}, {5, false}}};
  static constexpr std::array<Encoding, 5> anchors = {{{0, false}, {1, false}, {2, false}, {3, false}, {5, false}}};
  Encoding chosen{};
  bool checked = false;
  for (const Encoding& e : anchor ? anchors : continuations) {
    encode(n, e);
    if (check(n) <= 1.0) {
      chosen = e;
      checked = true;
      break;
    }
  }
  if (!checked) {
    // The one-cycle piece without the limit check (above): the last encoding tried, degree 5.
    enforce_limits = false;
    const bool passes = check(n) <= 1.0;
    enforce_limits = true;
    if (!passes) throw std::logic_error("segment writer: the piece it chose no longer fits");
  }
  // Commit: the lower level's state is the checked trial's, its deviations go to the statistics.
  state = trial;
  stats.max_error_mm = std::max({stats.max_error_mm, trial_worst.tool_mm, trial_worst.extra});
  stats.max_speed_error_mm_s = std::max(stats.max_speed_error_mm_s, trial_worst.speed_mm_s);
  replayed_before = trial_before;
  out->write(reinterpret_cast<const char*>(record.data()), static_cast<std::streamsize>(record.size()));
  stats.bytes += record.size();
  ++stats.pieces;
  if (anchor) ++stats.anchors;
  if (chosen.f32) ++stats.float32_pieces;
  ++stats.by_degree[static_cast<std::size_t>(chosen.degree)];
  ++index;
  held.erase(held.begin(), held.begin() + n);
  held_first += n;
}

std::vector<AxisBounds> axis_bounds(const Machine& machine, const AxisLayout& layout) {
  std::vector<AxisBounds> b;
  for (int i = 0; i < layout.size(); ++i) {
    const AxisLimits* a = machine.axis(layout.letter(i));
    if (a == nullptr) throw std::invalid_argument(fmt::format("axis_bounds: the machine has no {} axis", layout.letter(i)));
    b.push_back({a->max_velocity, a->max_acceleration, a->max_jerk});
  }
  return b;
}

}  // namespace kontur::segments
