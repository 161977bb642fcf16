#include "program_text.hpp"

#include <kontur/error.hpp>
#include <kontur/tolerances.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace kontur::compress::detail {

namespace {

bool fanuc_family(gcode::Dialect d) {
  return d == gcode::Dialect::fanuc || d == gcode::Dialect::haas || d == gcode::Dialect::mitsubishi;
}

std::string_view without_eol(std::string_view l) {
  while (!l.empty() && (l.back() == '\n' || l.back() == '\r')) l.remove_suffix(1);
  return l;
}

// Skips a word's value at `i` (spaces, a sign, then a number, a [bracketed expression] or a
// #parameter); false if there is none.
bool skip_value(const std::string& s, std::size_t& i) {
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  while (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  const std::size_t from = i;
  if (i < s.size() && s[i] == '[') {
    int depth = 0;
    for (; i < s.size(); ++i) {
      if (s[i] == '[') ++depth;
      if (s[i] == ']' && --depth == 0) {
        ++i;
        break;
      }
    }
    return depth == 0;
  }
  if (i < s.size() && s[i] == '#') {
    ++i;
    if (i < s.size() && s[i] == '<') {
      const std::size_t close = s.find('>', i);
      if (close == std::string::npos) return false;
      i = close + 1;
      return true;
    }
  }
  while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) != 0 || s[i] == '.')) ++i;
  return i > from;
}

}  // namespace

ProgramText::ProgramText(const std::string& path, gcode::Dialect dialect) : dialect_(dialect) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("file-open", fmt::format("{}: cannot open the program", path));
  text_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::size_t start = 0;
  while (start < text_.size()) {
    std::size_t end = text_.find('\n', start);
    end = end == std::string::npos ? text_.size() : end + 1;
    lines_.emplace_back(text_.data() + start, end - start);
    start = end;
  }
  const std::size_t nl = text_.find('\n');
  if (nl != std::string::npos && nl > 0 && text_[nl - 1] == '\r') eol_ = "\r\n";
}

std::string ProgramText::code_of(long line) const {
  const std::string_view raw = without_eol(this->line(line));
  std::string out;
  int depth = 0;
  for (const char c : raw) {
    if (c == ';') break;
    if (dialect_ != gcode::Dialect::sinumerik) {
      if (c == '(') ++depth;
      if (depth > 0) {
        if (c == ')') --depth;
        continue;
      }
    }
    if (c == '\t') {
      out += ' ';
      continue;
    }
    out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

bool ProgramText::plain_feed_line(long line) const {
  const std::string_view raw = without_eol(this->line(line));
  std::string s;
  for (const char c : raw) s += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (s.find_first_of("();%") != std::string::npos) return false;
  if (dialect_ != gcode::Dialect::sinumerik && s.find('=') != std::string::npos) return false;  // an assignment
  const std::size_t lead = s.find_first_not_of(" \t");
  if (lead == std::string::npos || s[lead] == '/') return false;
  for (std::size_t i = 0; i < s.size();) {
    const char c = s[i];
    if (c == ' ' || c == '\t') {
      ++i;
      continue;
    }
    if (c == 'G') {
      std::size_t j = i + 1;
      while (j < s.size() && s[j] == ' ') ++j;
      const std::size_t from = j;
      while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j])) != 0) ++j;
      if (j == from || (j < s.size() && s[j] == '.') || std::atoi(s.substr(from, j - from).c_str()) != 1) return false;
      i = j;
      continue;
    }
    if (c == 'N' || c == 'X' || c == 'Y' || c == 'Z' || c == 'F') {
      std::size_t j = i + 1;
      if (dialect_ == gcode::Dialect::sinumerik && j < s.size() && s[j] == '=') ++j;
      if (!skip_value(s, j)) return false;
      // an expression's operators and more values
      while (j < s.size() && (s[j] == '*' || s[j] == '/' || s[j] == '+' || s[j] == '-') && skip_value(s, ++j)) {
      }
      i = j;
      continue;
    }
    return false;
  }
  return true;
}

std::string ProgramText::n_word(long line) const {
  const std::string_view raw = without_eol(this->line(line));
  std::size_t i = raw.find_first_not_of(" \t");
  if (i == std::string_view::npos || (raw[i] != 'N' && raw[i] != 'n')) return {};
  std::size_t j = i + 1;
  while (j < raw.size() && std::isdigit(static_cast<unsigned char>(raw[j])) != 0) ++j;
  if (j == i + 1) return {};
  std::string word(1, 'N');
  word.append(raw.data() + i + 1, j - i - 1);
  return word;
}

bool ProgramText::next_lines_need_g1(long line) const {
  for (long l = line + 1; l <= static_cast<long>(line_count()); ++l) {
    const std::string s = code_of(l);
    std::size_t i = s.find_first_not_of(' ');
    if (i == std::string::npos) continue;
    if (s[i] == '#') continue;  // a parameter assignment
    if (s[i] == '%') return false;  // the end of the program
    bool axis = false;
    for (; i < s.size();) {
      const char c = s[i];
      if (c == ' ' || c == '/') {
        ++i;
        continue;
      }
      if (std::isalpha(static_cast<unsigned char>(c)) == 0) return true;  // not a plain word: assume the worst
      if (i + 1 < s.size() && std::isalpha(static_cast<unsigned char>(s[i + 1])) != 0) return true;  // a keyword
      std::size_t j = i + 1;
      while (j < s.size() && s[j] == ' ') ++j;
      const std::size_t from = j;
      if (!skip_value(s, j)) return true;
      const std::string value = s.substr(from, j - from);
      const bool literal = value.find_first_of("[#") == std::string::npos;
      const double x = literal ? std::atof(value.c_str()) : -1.0;
      if (c == 'G') {
        if (!literal) return true;
        const bool motion = x == 0.0 || x == 1.0 || x == 2.0 || x == 3.0 || x == 2.4 || x == 3.4 || x == 5.0 ||
                            x == 5.1 || x == 5.2 || x == 6.2 || x == 33.0 || x == 33.1 || x == 76.0 ||
                            (x >= 38.0 && x < 39.0) || x == 73.0 || x == 74.0 || (x >= 80.0 && x <= 89.0);
        if (motion) return false;
      } else if (c == 'M') {
        if (!literal) return true;
        if (x == 2.0 || x == 30.0) return false;
        if (x == 97.0 || x == 98.0 || x == 99.0) return true;
      } else if (c == 'O' || c == 'L') {
        return true;  // control flow, a subprogram
      } else if (std::string_view("XYZABCUVW").find(c) != std::string_view::npos) {
        axis = true;
      }
      i = j;
    }
    if (axis) return true;
  }
  return false;
}

RunWriter::RunWriter(gcode::Dialect dialect, const ProgramText& text, const gcode::ModalState& modal,
                     double tolerance_mm)
    : dialect_(dialect), text_(text), modal_(modal) {
  const bool inch = modal.units == gcode::Units::inch;
  unit_ = inch ? 25.4 : 1.0;
  // rounding within 2 % of the tolerance
  const int needed = static_cast<int>(std::ceil(-std::log10(0.02 * tolerance_mm / unit_)));
  decimals_ = std::clamp(needed, inch ? tolerances::compress_decimals_inch : tolerances::compress_decimals_mm, 9);
  decimal_point_ = fanuc_family(dialect);
}

std::string RunWriter::number(double v, int decimals) const {
  std::string s = fmt::format("{:.{}f}", v, decimals);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.' && !decimal_point_) s.pop_back();
  }
  if (s == "-0" || s == "-0." || s == "-") s = decimal_point_ ? "0." : "0";
  if (s.empty() || s == ".") s = decimal_point_ ? "0." : "0";
  return s;
}

std::string RunWriter::axes(const Vec3& target_mm, bool all, bool exact) {
  static constexpr char names[3] = {'X', 'Y', 'Z'};
  std::string w;
  for (int i = 0; i < 3; ++i) {
    const double t = target_mm[i] / unit_;
    std::string s = number(t, decimals_);
    // the run's last point exactly (within 1e-9), so that what follows starts where it did
    if (exact && std::abs(std::strtod(s.c_str(), nullptr) - t) > 1e-9) s = number(t, 9);
    if (all || s != number(position_[i], decimals_) || (exact && std::strtod(s.c_str(), nullptr) != position_[i])) {
      w += fmt::format(" {}{}", names[i], s);
      position_[i] = std::strtod(s.c_str(), nullptr);
    }
  }
  return w;
}

void RunWriter::block(std::string words) {
  if (!prefix_.empty()) {
    words = prefix_ + words;
    prefix_.clear();
  }
  out_.text += words;
  out_.text += text_.eol();
  ++out_.lines;
}

WrittenRun RunWriter::write(const std::vector<Vec3>& v, const std::vector<Piece>& pieces, double feed_mm_min,
                            long first_line) {
  out_ = {};
  const Vec3 start = v.front() / unit_;
  position_ = start;
  const int modal_plane = modal_.plane == gcode::Plane::xy ? 0 : modal_.plane == gcode::Plane::zx ? 1 : 2;
  int plane = modal_plane;
  const bool incremental = modal_.distance == gcode::DistanceMode::incremental;
  const std::string n = text_.n_word(first_line);
  prefix_ = n.empty() ? "" : n + " ";
  if (incremental) prefix_ += "G90 ";
  const std::string feed = fmt::format(" F{}", number(feed_mm_min / unit_, 4));
  bool first = true;
  auto f = [&]() -> std::string {
    if (!first) return "";
    first = false;
    return feed;
  };
  static constexpr std::array<const char*, 3> plane_codes{"G17", "G18", "G19"};
  static constexpr char offset_names[3] = {'I', 'J', 'K'};
  const bool sinumerik = dialect_ == gcode::Dialect::sinumerik;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& p = pieces[k];
    const bool last = k + 1 == pieces.size();
    const Vec3& end = v[p.last];
    const std::size_t before = out_.lines;
    switch (p.kind) {
      case PieceKind::line: {
        block("G1" + axes(end, false, last) + f());
        break;
      }
      case PieceKind::arc: {
        const Vec3 from = position_;
        std::string words = p.plane != plane ? std::string(plane_codes[static_cast<std::size_t>(p.plane)]) + " " : "";
        const std::string to = axes(end, false, last);
        const std::array<int, 3> ax = plane_axes(p.plane);
        if (from[ax[0]] == position_[ax[0]] && from[ax[1]] == position_[ax[1]]) {
          block("G1" + to + f());  // the arc's chord rounds to nothing in its plane: a line (checked)
          break;
        }
        plane = p.plane;
        words += p.counter_clockwise ? "G3" : "G2";
        words += to;
        const Vec3 c = p.centre / unit_;
        const bool absolute = modal_.arc_distance == gcode::DistanceMode::absolute;
        for (const int a : {ax[0], ax[1]}) {
          const double off = absolute ? c[a] : c[a] - from[a];
          words += fmt::format(" {}{}", offset_names[a], number(off, decimals_));
        }
        block(words + f());
        break;
      }
      case PieceKind::arc_3d: {
        if (sinumerik) {
          const Vec3 via = p.via[0] / unit_;
          const std::string to = axes(end, true, last);
          block(fmt::format("CIP{} I1={} J1={} K1={}{}", to, number(via.x(), decimals_), number(via.y(), decimals_),
                            number(via.z(), decimals_), f()));
        } else {
          block("G02.4" + axes(p.via[0], true) + f());
          block(axes(end, true, last).substr(1));
        }
        break;
      }
      case PieceKind::conic: {
        std::string words = "CONIC" + axes(end, true, last);
        for (int j = 0; j < 3; ++j) {
          const Vec3 q = p.via[static_cast<std::size_t>(j)] / unit_;
          words += fmt::format(" I{}={} J{}={} K{}={}", j + 1, number(q.x(), decimals_), j + 1,
                               number(q.y(), decimals_), j + 1, number(q.z(), decimals_));
        }
        block(words + f());
        break;
      }
      case PieceKind::spline: {
        const NurbsCurve& s = *p.spline;
        const bool linuxcnc = dialect_ == gcode::Dialect::linuxcnc;
        const std::string code = linuxcnc ? "G6.2" : "G06.2";
        const std::string weight = linuxcnc ? " R1" : "";
        const int knot_decimals = std::max(6, decimals_ + 2);
        const auto& knots = s.knots();
        const auto& points = s.points();
        const std::size_t order = static_cast<std::size_t>(s.degree()) + 1;
        for (std::size_t i = 0; i < points.size(); ++i) {
          const std::string kw = fmt::format("K{}", number(knots[i], knot_decimals));
          if (i == 0) {
            // the first control point is the current position: written as the control has it
            std::string words = fmt::format("{} P{} {}", code, order, kw);
            for (int a = 0; a < 3; ++a) words += fmt::format(" {}{}", "XYZ"[a], number(position_[a], decimals_));
            block(words + weight + f());
          } else {
            const bool end_point = i + 1 == points.size();
            block(kw + axes(end_point ? end : points[i], end_point, end_point && last) + weight);
          }
        }
        for (std::size_t i = points.size(); i < points.size() + order; ++i)
          block((linuxcnc ? "G6.2 K" : "K") + number(knots[i], knot_decimals));
        break;
      }
    }
    out_.piece_lines.emplace_back(before, out_.lines - 1);
  }
  if (plane != modal_plane) block(plane_codes[static_cast<std::size_t>(modal_plane)]);
  if (incremental) block("G91");
  return out_;
}

}  // namespace kontur::compress::detail
