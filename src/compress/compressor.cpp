#include <kontur/compress/compressor.hpp>
#include <kontur/error.hpp>
#include <kontur/tolerances.hpp>

#include "two_way_distance.hpp"
#include "program_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace kontur::compress {

CurveKinds default_kinds(gcode::Dialect dialect) noexcept {
  using gcode::Dialect;
  CurveKinds k;
  k.arcs = true;
  k.arcs_3d = dialect == Dialect::fanuc || dialect == Dialect::mitsubishi || dialect == Dialect::sinumerik;
  k.splines = dialect == Dialect::linuxcnc || dialect == Dialect::fanuc || dialect == Dialect::mitsubishi;
  k.conics = false;
  return k;
}

namespace {

using gcode::Block;
using gcode::BlockType;

// What the compressor keeps of a block of the input.
struct BlockRecord {
  long line = 0;
  BlockType type = BlockType::line;
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  bool main_file = false, extra_axes = false;
  gcode::Feed feed;
  gcode::ModalState modal;
  Eigen::Matrix3d frame_linear = Eigen::Matrix3d::Identity();
  Vec3 frame_origin = Vec3::Zero();
  bool in_run = false;
};

bool is_feed(BlockType t) { return t != BlockType::rapid && t != BlockType::dwell; }

bool same_modal(const gcode::ModalState& a, const gcode::ModalState& b) {
  return a.units == b.units && a.distance == b.distance && a.arc_distance == b.arc_distance && a.plane == b.plane &&
         a.feed_mode == b.feed_mode && a.path_control == b.path_control &&
         a.blend_tolerance_mm == b.blend_tolerance_mm && a.naive_cam_tolerance_mm == b.naive_cam_tolerance_mm &&
         a.cutter_comp == b.cutter_comp && a.work_offset == b.work_offset && a.tool_length_mm == b.tool_length_mm;
}

// A rotation (orthonormal, determinant +1): arcs stay arcs with their sense in program coordinates.
bool rotation_only(const Eigen::Matrix3d& l) {
  return (l.transpose() * l - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12 && l.determinant() > 0.0;
}

// A run: blocks first .. last (indices into the records).
struct Run {
  std::size_t first = 0, last = 0;
};

BlockRecord record_of(const Block& b, const std::string& name) {
    BlockRecord r;
    r.line = b.location.line;
    r.type = b.type;
    r.start = b.start;
    r.end = b.end;
    r.main_file = b.location.file && *b.location.file == name;
    r.extra_axes = b.moves_extra_axes();
    r.feed = b.feed;
    r.modal = b.modal;
    r.frame_linear = b.frame_linear;
    r.frame_origin = b.frame_origin;
    return r;
}

// The blocks of the program `name`, read through Kontur's reader (the whole program is checked
// first: an error throws before any block is kept).
std::vector<BlockRecord> read_blocks(const std::string& name, const gcode::ReaderOptions& options,
                                     gcode::DialectChoice& dialect) {
  std::vector<BlockRecord> records;
  dialect = gcode::for_each_block(name, [&](const Block& b) { records.push_back(record_of(b, name)); }, options);
  return records;
}

// The runs of compressible G1 blocks.
std::vector<Run> find_runs(std::vector<BlockRecord>& blocks, const detail::ProgramText& text) {
  std::vector<int> executions(text.line_count() + 2, 0);
  for (const BlockRecord& b : blocks)
    if (b.main_file && b.line >= 1 && b.line <= static_cast<long>(text.line_count())) ++executions[b.line];
  auto compressible = [&](const BlockRecord& b) {
    return b.type == BlockType::line && b.main_file && b.line >= 1 && b.line <= static_cast<long>(text.line_count()) &&
           executions[b.line] == 1 && !b.extra_axes && b.modal.cutter_comp == gcode::CutterComp::off &&
           b.feed.mode == gcode::FeedMode::units_per_minute && b.feed.value > 0.0 && b.start.allFinite() &&
           b.end.allFinite() && rotation_only(b.frame_linear) && text.plain_feed_line(b.line);
  };
  auto continues = [&](const BlockRecord& a, const BlockRecord& b) {
    return b.line == a.line + 1 && b.feed.value == a.feed.value && same_modal(a.modal, b.modal) &&
           a.frame_linear == b.frame_linear && a.frame_origin == b.frame_origin && b.start == a.end;
  };
  std::vector<Run> runs;
  std::size_t i = 0;
  while (i < blocks.size()) {
    if (!compressible(blocks[i])) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < blocks.size() && compressible(blocks[j + 1]) && continues(blocks[j], blocks[j + 1])) ++j;
    if (j > i) runs.push_back(Run{i, j});  // two lines or more
    i = j + 1;
  }
  return runs;
}

// The run's vertices, without repeated points (a zero-length line adds none).
std::vector<Vec3> run_vertices(const std::vector<BlockRecord>& blocks, const Run& run) {
  std::vector<Vec3> v{blocks[run.first].start};
  for (std::size_t k = run.first; k <= run.last; ++k)
    if (blocks[k].end != v.back()) v.push_back(blocks[k].end);
  return v;
}

// A run as it is being written: its vertices in machine coordinates (what is checked) and in the
// program's frame [mm] (what is fitted and written), its pieces and their text.
struct RunState {
  std::vector<Vec3> machine, program;
  std::vector<Piece> pieces;
  detail::WrittenRun out;
  bool active = false;
  long output_line = 0;                  // its first line in the output (0: not written)
  std::vector<double> piece_deviation;  // the check's, per piece [mm]
};

// What the check found wrong in the written program.
struct CheckFailure {
  std::size_t run = 0, piece = 0;
};

// Which run and piece each written output line belongs to: (first line, last line, run, piece) of
// every active piece, in line order.
struct PieceLines {
  long first = 0, last = 0;
  std::size_t run = 0, piece = 0;
};

std::vector<PieceLines> piece_lines(const std::vector<RunState>& runs) {
  std::vector<PieceLines> out;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const RunState& st = runs[r];
    if (!st.active) continue;
    for (std::size_t p = 0; p < st.out.piece_lines.size(); ++p)
      out.push_back(PieceLines{st.output_line + static_cast<long>(st.out.piece_lines[p].first),
                               st.output_line + static_cast<long>(st.out.piece_lines[p].second), r, p});
  }
  return out;
}

// The output line `line` belongs to which run and piece (false: none).
bool locate(const std::vector<PieceLines>& index, long line, CheckFailure& where) {
  const auto it = std::upper_bound(index.begin(), index.end(), line,
                                   [](long l, const PieceLines& p) { return l < p.first; });
  if (it == index.begin()) return false;
  const PieceLines& p = *(it - 1);
  if (line > p.last) return false;
  where = {p.run, p.piece};
  return true;
}

// The independent check: the output read again by Kontur's reader; for each written piece the
// two-way distance between its blocks (sampled) and its programmed lines (every sample from the
// lines, every programmed vertex from the samples' polyline); and the blocks outside the runs
// compared with the input's (same type, same end point). Sets piece_deviation of every active run;
// a block the reader refuses marks its piece as straying (infinity).
void check_output(const std::string& name, const std::string& output, const gcode::ReaderOptions& options,
                  const std::vector<BlockRecord>& input, const std::vector<Run>& runs, std::vector<RunState>& states,
                  double tol) {
  std::vector<std::vector<std::vector<Vec3>>> samples(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) {
    states[r].piece_deviation.assign(states[r].pieces.size(), 0.0);
    samples[r].assign(states[r].pieces.size(), {});
  }
  std::vector<BlockRecord> outside;
  const std::vector<PieceLines> index = piece_lines(states);
  try {
    gcode::Reader reader(name, output, options);
    Block b;
    while (reader.next(b)) {
      const BlockRecord rec = record_of(b, name);
      CheckFailure at;
      if (!rec.main_file || !locate(index, rec.line, at)) {
        outside.push_back(rec);
        continue;
      }
      std::vector<Vec3>& s = samples[at.run][at.piece];
      if (s.empty()) s.push_back(rec.start);
      if (const Curve* c = b.curve()) {
        const double len = b.length_mm().value_or((b.end - b.start).norm());
        const std::size_t min_count = b.type == BlockType::line ? 1 : tolerances::compress_check_samples_per_line;
        // at least min_count steps, none longer than the check's step [mm]
        const double steps = std::ceil(std::min(1e6, len / (tolerances::compress_check_step_tolerances * tol)));
        detail::append_samples(*c, std::max(min_count, static_cast<std::size_t>(steps)), s);
      }
    }
  } catch (const InputError& e) {
    // the reader refused a written block: "NAME:LINE:COLUMN: ..." names its line
    const std::string what = e.what();
    long line = 0;
    if (what.rfind(name + ":", 0) == 0) line = std::atol(what.c_str() + name.size() + 1);
    CheckFailure at;
    if (!locate(index, line, at)) throw;
    states[at.run].piece_deviation[at.piece] = std::numeric_limits<double>::infinity();
    return;
  }
  for (std::size_t r = 0; r < runs.size(); ++r) {
    RunState& st = states[r];
    if (!st.active) continue;
    for (std::size_t p = 0; p < st.pieces.size(); ++p) {
      const std::vector<Vec3>& s = samples[r][p];
      if (s.size() < 2) {
        st.piece_deviation[p] = std::numeric_limits<double>::infinity();  // its blocks went missing
        continue;
      }
      const Piece& piece = st.pieces[p];
      st.piece_deviation[p] =
          detail::two_way_distance(std::span(st.machine).subspan(piece.first, piece.last - piece.first + 1), s, tol);
    }
  }
  // outside the runs: the same blocks, ending at the same points
  std::vector<const BlockRecord*> before;
  for (std::size_t i = 0, k = 0; i < input.size(); ++i) {
    while (k < runs.size() && runs[k].last < i) ++k;
    const bool inside = k < runs.size() && runs[k].first <= i && i <= runs[k].last && states[k].active;
    if (!inside) before.push_back(&input[i]);
  }
  if (before.size() != outside.size())
    throw std::logic_error(fmt::format("compress: the output has {} blocks outside the runs, the input {}",
                                       outside.size(), before.size()));
  for (std::size_t i = 0; i < before.size(); ++i)
    if (before[i]->type != outside[i].type || (before[i]->end - outside[i].end).norm() > tol)
      throw std::logic_error(fmt::format("compress: the block of input line {} comes out as a {} ending {:.6f} mm away",
                                         before[i]->line, gcode::to_string(outside[i].type),
                                         (before[i]->end - outside[i].end).norm()));
}

}  // namespace

CompressResult compress_program(const std::string& path, const CompressOptions& options) {
  const double tol = options.tolerance_mm;
  if (!(tol > 0.0) || !std::isfinite(tol))
    throw InputError("tolerance", fmt::format("--tolerance {}: must be a positive number of mm", tol));
  CompressResult result;
  std::vector<BlockRecord> blocks = read_blocks(path, options.reader, result.dialect);
  gcode::ReaderOptions reader = options.reader;
  reader.dialect = result.dialect.dialect;
  const detail::ProgramText text(path, result.dialect.dialect);

  result.input_blocks = blocks.size();
  for (const BlockRecord& b : blocks) result.feed_blocks_in += is_feed(b.type) ? 1 : 0;
  const std::vector<Run> runs = find_runs(blocks, text);

  // Fit and write every run.
  std::vector<RunState> states(runs.size());
  result.runs.resize(runs.size());
  auto write = [&](std::size_t k) {
    RunState& st = states[k];
    RunReport& rep = result.runs[k];
    const BlockRecord& first = blocks[runs[k].first];
    detail::RunWriter w(result.dialect.dialect, text, first.modal, tol);
    st.out = w.write(st.program, st.pieces, first.feed.value, rep.first_line);
    st.active = st.out.lines < rep.lines_in;
    if (!st.active) rep.kept = "no fewer blocks";
  };
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Run& run = runs[k];
    const BlockRecord& first = blocks[run.first];
    RunState& st = states[k];
    RunReport& rep = result.runs[k];
    rep.first_line = first.line;
    rep.last_line = blocks[run.last].line;
    rep.lines_in = run.last - run.first + 1;
    st.machine = run_vertices(blocks, run);
    // fitted and written in the program's frame (machine = L p + o, L a rotation), checked in the machine's
    st.program.resize(st.machine.size());
    for (std::size_t i = 0; i < st.machine.size(); ++i)
      st.program[i] = first.frame_linear.transpose() * (st.machine[i] - first.frame_origin);
    const std::vector<Vec3>& v = st.program;
    if (v.size() < 3) {
      rep.kept = "fewer than two lines of non-zero length";
      continue;
    }
    // The motion mode after the run: if a later block relies on the modal G1, the run ends with its
    // last line, as a G1.
    if (text.next_lines_need_g1(rep.last_line)) {
      const std::vector<Vec3> head(v.begin(), v.end() - 1);
      st.pieces = fit_pieces(head, tol, options.kinds);
      Piece last;
      last.first = v.size() - 2;
      last.last = v.size() - 1;
      st.pieces.push_back(last);
    } else {
      st.pieces = fit_pieces(v, tol, options.kinds);
    }
    write(k);
  }

  // Assemble and check; a piece the check finds out of tolerance is written as its lines, and the
  // whole is checked again.
  for (;;) {
    std::string out;
    out.reserve(text.size());
    long out_line = 1;
    std::size_t k = 0;
    for (long line = 1; line <= static_cast<long>(text.line_count()); ++line) {
      while (k < runs.size() && (!states[k].active || result.runs[k].last_line < line)) ++k;
      if (k < runs.size() && states[k].active && result.runs[k].first_line == line) {
        out += states[k].out.text;
        states[k].output_line = out_line;
        out_line += static_cast<long>(states[k].out.lines);
        line = result.runs[k].last_line;
        continue;
      }
      out += text.line(line);
      ++out_line;
    }
    check_output(path, out, reader, blocks, runs, states, tol);
    bool again = false;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      RunState& st = states[r];
      if (!st.active) continue;
      std::vector<Piece> kept;
      bool changed = false;
      for (std::size_t p = 0; p < st.pieces.size(); ++p) {
        if (st.piece_deviation[p] <= tol || st.pieces[p].kind == PieceKind::line) {
          kept.push_back(st.pieces[p]);
          continue;
        }
        changed = true;
        ++result.pieces_rewritten;
        for (std::size_t i = st.pieces[p].first; i < st.pieces[p].last; ++i) {
          Piece line;
          line.first = i;
          line.last = i + 1;
          kept.push_back(line);
        }
      }
      if (!changed) continue;
      st.pieces = std::move(kept);
      write(r);
      again = true;
    }
    result.text = std::move(out);
    if (!again) break;
  }

  result.feed_blocks_out = result.feed_blocks_in;
  result.max_deviation_mm = 0.0;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    RunReport& rep = result.runs[k];
    const RunState& st = states[k];
    if (!st.active) {
      if (rep.kept.empty()) rep.kept = "no fewer blocks";
      rep.blocks_out = rep.lines_in;
      continue;
    }
    rep.output_line = st.output_line;
    rep.blocks_out = st.out.lines;
    for (const Piece& p : st.pieces) ++rep.pieces[static_cast<std::size_t>(p.kind)];
    for (const double d : st.piece_deviation) rep.deviation_mm = std::max(rep.deviation_mm, d);
    result.feed_blocks_out = result.feed_blocks_out - rep.lines_in + rep.blocks_out;
    result.max_deviation_mm = std::max(result.max_deviation_mm, rep.deviation_mm);
  }
  return result;
}

}  // namespace kontur::compress
