#include <kontur/error.hpp>
#include <kontur/machine.hpp>

#include <fmt/format.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

namespace kontur {
namespace {

constexpr double kInch = 25.4;                 // [mm/inch]
constexpr double kDefaultJerkTime = 0.01;      // [s] acceleration ramp of an axis without a jerk limit

[[noreturn]] void fail(const std::string& source, const std::string& rule, const std::string& what) {
  throw InputError(rule, fmt::format("{}: {}", source, what));
}

void check_positive(const std::string& source, const std::string& field, double v) {
  if (!std::isfinite(v) || v <= 0.0)
    fail(source, "limit-positive", fmt::format("{} = {}: must be finite and > 0", field, v));
}

std::string read_text(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError("file-missing", fmt::format("{}: no such file", file.string()));
  if (std::filesystem::is_directory(file, ec))
    throw InputError("file-not-regular", fmt::format("{}: is a directory, not a machine file", file.string()));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("file-unreadable", fmt::format("{}: cannot be opened for reading", file.string()));
  std::ostringstream b;
  b << in.rdbuf();
  return b.str();
}

bool is_rotary(char c) { return c == 'A' || c == 'B' || c == 'C'; }
// The canonical order of the axes, and LinuxCNC 2.7's numbering of [AXIS_n] (X = 0 .. W = 8).
constexpr const char* kAxisOrder = "XYZABCUVW";

}  // namespace

const AxisLimits* Machine::axis(char n) const noexcept {
  for (const auto& a : axes)
    if (a.name == n) return &a;
  return nullptr;
}

Machine default_machine() {
  Machine m;
  m.name = "Kontur default 3-axis mill";
  m.source = "embedded default";
  for (char c : {'X', 'Y', 'Z'}) m.axes.push_back({c, false, 200.0, 2000.0, 50000.0});
  m.max_feed_mm_s = 10000.0 / 60.0;
  m.rapid_feed_mm_s = 12000.0 / 60.0;
  m.chord_tolerance_mm = 0.001;
  m.path_tolerance_mm = 0.01;
  m.servo_period_s = 0.001;
  return m;
}

void validate(const Machine& m) {
  const std::string& src = m.source;
  if (m.axis('X') == nullptr && m.axis('Y') == nullptr && m.axis('Z') == nullptr)
    fail(src, "axis-missing", "no linear axis: at least one of X, Y, Z is required");
  for (std::size_t i = 0; i < m.axes.size(); ++i) {
    const AxisLimits& a = m.axes[i];
    for (std::size_t j = 0; j < i; ++j)
      if (m.axes[j].name == a.name) fail(src, "axis-twice", fmt::format("axis {} is given twice", a.name));
    check_positive(src, fmt::format("axis {} max velocity [{}/s]", a.name, a.rotary ? "deg" : "mm"), a.max_velocity);
    check_positive(src, fmt::format("axis {} max acceleration [{}/s^2]", a.name, a.rotary ? "deg" : "mm"), a.max_acceleration);
    check_positive(src, fmt::format("axis {} max jerk [{}/s^3]", a.name, a.rotary ? "deg" : "mm"), a.max_jerk);
    if (!(a.min_position < a.max_position) || std::isnan(a.min_position) || std::isnan(a.max_position))
      fail(src, "position-range", fmt::format("axis {}: min position {} must be below max position {}", a.name,
                                              a.min_position, a.max_position));
  }
  check_positive(src, "max feed [mm/s]", m.max_feed_mm_s);
  check_positive(src, "rapid feed [mm/s]", m.rapid_feed_mm_s);
  check_positive(src, "chord tolerance [mm]", m.chord_tolerance_mm);
  check_positive(src, "path tolerance [mm]", m.path_tolerance_mm);
  if (!(m.servo_period_s >= 1e-5 && m.servo_period_s <= 0.1))
    fail(src, "servo-period-range", fmt::format("servo period {} s: must be in [10 us, 100 ms]", m.servo_period_s));
}

Machine read_machine_toml(const std::filesystem::path& file) {
  const std::string text = read_text(file);
  const std::string src = file.string();
  toml::table doc;
  try {
    doc = toml::parse(text, src);
  } catch (const toml::parse_error& e) {
    fail(fmt::format("{}:{}:{}", src, e.source().begin.line, e.source().begin.column), "toml-syntax",
         fmt::format("not valid TOML: {}", e.description()));
  }
  Machine m = default_machine();
  m.source = src;
  m.name = file.stem().string();
  auto number = [&](const toml::node& n, const std::string& field) {
    if (auto v = n.value<double>()) return *v;
    fail(fmt::format("{}:{}", src, n.source().begin.line), "not-a-number", fmt::format("{} is not a number", field));
  };
  static const std::map<std::string, double Machine::*> scalars = {
      {"chord_tolerance_mm", &Machine::chord_tolerance_mm}, {"path_tolerance_mm", &Machine::path_tolerance_mm},
      {"servo_period_s", &Machine::servo_period_s}};
  for (const auto& [key, node] : doc) {
    const std::string k(key.str());
    if (k == "name") {
      if (auto s = node.value<std::string>()) m.name = *s;
    } else if (k == "subroutine_path") {
      const toml::array* folders = node.as_array();
      if (folders == nullptr)
        fail(fmt::format("{}:{}", src, node.source().begin.line), "subroutine-path",
             "subroutine_path must be an array of folders");
      for (const auto& f : *folders) {
        const auto folder = f.value<std::string>();
        if (!folder)
          fail(fmt::format("{}:{}", src, f.source().begin.line), "subroutine-path",
               "subroutine_path: every folder is a string");
        m.subroutine_path.push_back((file.parent_path() / *folder).lexically_normal().string());
      }
    } else if (k == "dialect") {
      const auto name = node.value<std::string>();
      m.dialect = name ? gcode::parse_dialect(*name) : std::nullopt;
      if (!m.dialect)
        fail(fmt::format("{}:{}", src, node.source().begin.line), "dialect",
             fmt::format("dialect {}: not a G-code dialect (expected one of {})", name.value_or("(not a string)"),
                         gcode::dialect_names()));
    } else if (k == "tool_table") {
      const auto path = node.value<std::string>();
      if (!path)
        fail(fmt::format("{}:{}", src, node.source().begin.line), "tool-table", "tool_table must be a file name (a string)");
      m.tool_table = (file.parent_path() / *path).lexically_normal().string();
    } else if (k == "tool_table_units") {
      const auto u = node.value<std::string>();
      if (!u || (*u != "mm" && *u != "inch"))
        fail(fmt::format("{}:{}", src, node.source().begin.line), "tool-table",
             "tool_table_units must be \"mm\" or \"inch\"");
      m.tool_table_mm_per_unit = *u == "inch" ? kInch : 1.0;
    } else if (k == "max_feed_mm_min") {
      m.max_feed_mm_s = number(node, k) / 60.0;
    } else if (k == "rapid_feed_mm_min") {
      m.rapid_feed_mm_s = number(node, k) / 60.0;
    } else if (scalars.count(k) != 0) {
      m.*(scalars.at(k)) = number(node, k);
    } else if (k == "axes") {
      const toml::table* axes = node.as_table();
      if (axes == nullptr) fail(src, "axes-shape", "axes must be a table of [axes.X] sections");
      m.axes.clear();  // the file's axes are the machine's axes, all of them
      for (const auto& [axis_key, axis_node] : *axes) {
        const std::string an(axis_key.str());
        if (an.size() != 1 || std::string(kAxisOrder).find(static_cast<char>(std::toupper(static_cast<unsigned char>(an[0])))) == std::string::npos)
          fail(fmt::format("{}:{}", src, axis_node.source().begin.line), "axis-name",
               fmt::format("axes.{}: an axis is one of X Y Z A B C U V W (A B C rotary in deg, the others linear in mm)", an));
        const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(an[0])));
        AxisLimits* a = nullptr;
        for (auto& existing : m.axes)
          if (existing.name == c) a = &existing;
        if (a == nullptr) {
          m.axes.push_back({c, is_rotary(c), 0.0, 0.0, 0.0});
          a = &m.axes.back();
        }
        const toml::table* t = axis_node.as_table();
        if (t == nullptr) fail(src, "axes-shape", fmt::format("axes.{} must be a table", an));
        for (const auto& [f, v] : *t) {
          const std::string fk(f.str());
          const std::string field = fmt::format("axes.{}.{}", an, fk);
          if (fk == "max_velocity") a->max_velocity = number(v, field);
          else if (fk == "max_acceleration") a->max_acceleration = number(v, field);
          else if (fk == "max_jerk") a->max_jerk = number(v, field);
          else if (fk == "min_position") a->min_position = number(v, field);
          else if (fk == "max_position") a->max_position = number(v, field);
          else
            fail(fmt::format("{}:{}", src, v.source().begin.line), "unknown-field",
                 fmt::format("unknown field {} (expected max_velocity, max_acceleration, max_jerk, min_position, "
                             "max_position)",
                             field));
        }
      }
    } else {
      fail(fmt::format("{}:{}", src, node.source().begin.line), "unknown-field",
           fmt::format("unknown field \"{}\" (expected name, dialect, subroutine_path, tool_table, tool_table_units, max_feed_mm_min, rapid_feed_mm_min, "
                       "chord_tolerance_mm, path_tolerance_mm, servo_period_s, axes)",
                       k));
    }
  }
  // TOML tables are unordered: keep the canonical coordinate order X Y Z A B C U V W.
  std::sort(m.axes.begin(), m.axes.end(), [](const AxisLimits& a, const AxisLimits& b) {
    return std::string(kAxisOrder).find(a.name) < std::string(kAxisOrder).find(b.name);
  });
  validate(m);
  return m;
}

Machine read_linuxcnc_ini(const std::filesystem::path& file) {
  const std::string text = read_text(file);
  const std::string src = file.string();
  // section -> key -> (value, line); the last of repeated keys wins, as in LinuxCNC.
  std::map<std::string, std::map<std::string, std::pair<std::string, int>>> ini;
  std::string section;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return std::string();
    const auto e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
  };
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#' || t[0] == ';') continue;
    if (t[0] == '[') {
      const auto close = t.find(']');
      if (close == std::string::npos)
        fail(fmt::format("{}:{}", src, line_no), "ini-syntax", fmt::format("section header \"{}\" has no ]", t));
      section = t.substr(1, close - 1);
      continue;
    }
    const auto eq = t.find('=');
    if (eq == std::string::npos) continue;  // LinuxCNC ignores such lines too
    ini[section][trim(t.substr(0, eq))] = {trim(t.substr(eq + 1)), line_no};
  }
  auto get = [&](const std::string& sec, const std::string& key) -> const std::pair<std::string, int>* {
    auto s = ini.find(sec);
    if (s == ini.end()) return nullptr;
    auto k = s->second.find(key);
    return k == s->second.end() ? nullptr : &k->second;
  };
  auto number = [&](const std::string& sec, const std::string& key) -> std::optional<double> {
    const auto* v = get(sec, key);
    if (v == nullptr) return std::nullopt;
    try {
      std::size_t used = 0;
      const double d = std::stod(v->first, &used);
      if (trim(v->first.substr(used)).empty()) return d;
    } catch (const std::exception&) {
    }
    fail(fmt::format("{}:{}", src, v->second), "not-a-number", fmt::format("[{}] {} = {} is not a number", sec, key, v->first));
  };
  Machine m = default_machine();
  m.source = src;
  if (const auto* name = get("EMC", "MACHINE")) m.name = name->first;
  double unit = 1.0;  // [mm per machine unit]
  if (const auto* u = get("TRAJ", "LINEAR_UNITS")) {
    std::string v = u->first;
    std::transform(v.begin(), v.end(), v.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (v == "inch" || v == "in" || v == "imperial") unit = kInch;
    else if (v == "mm" || v == "metric") unit = 1.0;
    else fail(fmt::format("{}:{}", src, u->second), "linear-units", fmt::format("[TRAJ] LINEAR_UNITS = {}: expected mm or inch", u->first));
  }
  std::string coords = "XYZ";
  if (const auto* c = get("TRAJ", "COORDINATES")) {
    coords.clear();
    for (char ch : c->first)
      if (std::isalpha(static_cast<unsigned char>(ch))) coords += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  }
  const double jerk_time = number("KONTUR", "JERK_TIME").value_or(kDefaultJerkTime);
  check_positive(src, "[KONTUR] JERK_TIME [s]", jerk_time);
  m.axes.clear();
  for (const char c : coords)
    if (std::string(kAxisOrder).find(c) == std::string::npos)
      fail(fmt::format("{}:{}", src, get("TRAJ", "COORDINATES")->second), "coordinates",
           fmt::format("[TRAJ] COORDINATES = {}: '{}' is not an axis (X Y Z A B C U V W)", get("TRAJ", "COORDINATES")->first, c));
  // An [AXIS_<letter>] section for an axis COORDINATES lacks: the file disagrees with itself.
  for (const char c : std::string(kAxisOrder))
    if (ini.count(fmt::format("AXIS_{}", c)) != 0 && coords.find(c) == std::string::npos)
      fail(src, "coordinates",
           fmt::format("[AXIS_{}] is given but [TRAJ] COORDINATES = {} has no {}: add {} to COORDINATES or remove the "
                       "section",
                       c, coords, c, c));
  for (std::size_t i = 0; i < coords.size(); ++i) {
    const char c = coords[i];
    bool seen = false;
    for (const auto& a : m.axes) seen = seen || a.name == c;
    if (seen) continue;  // gantries: the first joint of a letter
    // LinuxCNC 2.7 numbers [AXIS_n] by the letter (X = 0 .. C = 5); 2.8+ names [AXIS_X] for the
    // axis and [JOINT_n] for the joints, in coordinate order.
    const auto letter_index = std::string(kAxisOrder).find(c);
    std::string sec;
    for (const std::string& cand : {fmt::format("AXIS_{}", c), fmt::format("AXIS_{}", letter_index), fmt::format("JOINT_{}", i)})
      if (ini.count(cand) != 0) {
        sec = cand;
        break;
      }
    if (sec.empty()) fail(src, "axis-section", fmt::format("no [AXIS_{}], [AXIS_{}] or [JOINT_{}] section for coordinate {}", c, letter_index, i, c));
    const double scale = is_rotary(c) ? 1.0 : unit;
    AxisLimits a{c, is_rotary(c), 0.0, 0.0, 0.0};
    const auto vel = number(sec, "MAX_VELOCITY");
    const auto acc = number(sec, "MAX_ACCELERATION");
    if (!vel) fail(src, "missing-key", fmt::format("[{}] MAX_VELOCITY is missing", sec));
    if (!acc) fail(src, "missing-key", fmt::format("[{}] MAX_ACCELERATION is missing", sec));
    a.max_velocity = *vel * scale;
    a.max_acceleration = *acc * scale;
    a.max_jerk = number(sec, "MAX_JERK").value_or(*acc / jerk_time) * scale;
    if (auto v = number(sec, "MIN_LIMIT")) a.min_position = *v * scale;
    if (auto v = number(sec, "MAX_LIMIT")) a.max_position = *v * scale;
    m.axes.push_back(a);
  }
  if (auto v = number("TRAJ", "MAX_LINEAR_VELOCITY")) m.max_feed_mm_s = *v * unit;
  else if (auto w = number("TRAJ", "MAX_VELOCITY")) m.max_feed_mm_s = *w * unit;
  m.rapid_feed_mm_s = m.max_feed_mm_s;  // LinuxCNC traverses at the trajectory's maximum velocity
  if (auto v = number("EMCMOT", "SERVO_PERIOD")) m.servo_period_s = *v * 1e-9;
  if (auto v = number("KONTUR", "CHORD_TOLERANCE")) m.chord_tolerance_mm = *v * unit;
  if (auto v = number("KONTUR", "PATH_TOLERANCE")) m.path_tolerance_mm = *v * unit;
  if (const auto* p = get("RS274NGC", "SUBROUTINE_PATH")) {  // folders separated by ':', relative to the INI
    std::size_t at = 0;
    while (at <= p->first.size()) {
      const std::size_t colon = std::min(p->first.find(':', at), p->first.size());
      const std::string folder = trim(p->first.substr(at, colon - at));
      if (!folder.empty()) m.subroutine_path.push_back((file.parent_path() / folder).lexically_normal().string());
      at = colon + 1;
    }
  }
  if (auto v = number("RS274NGC", "CENTER_ARC_RADIUS_TOLERANCE_MM")) {
    check_positive(src, "[RS274NGC] CENTER_ARC_RADIUS_TOLERANCE_MM [mm]", *v);
    m.arc_radius_tolerance_mm = *v;
  }
  if (auto v = number("RS274NGC", "CENTER_ARC_RADIUS_TOLERANCE_INCH")) {
    check_positive(src, "[RS274NGC] CENTER_ARC_RADIUS_TOLERANCE_INCH [in]", *v);
    m.arc_radius_tolerance_inch = *v;
  }
  // relative to the INI, in the machine's units; a configuration copied without its table (the file
  // is missing) runs as without one
  if (const auto* t = get("EMCIO", "TOOL_TABLE")) {
    const std::filesystem::path table = (file.parent_path() / trim(t->first)).lexically_normal();
    std::error_code ec;
    if (std::filesystem::is_regular_file(table, ec)) {
      m.tool_table = table.string();
      m.tool_table_mm_per_unit = unit;
    }
  }
  if (const auto* d = get("KONTUR", "DIALECT")) {
    m.dialect = gcode::parse_dialect(d->first);
    if (!m.dialect)
      fail(fmt::format("{}:{}", src, d->second), "dialect",
           fmt::format("[KONTUR] DIALECT = {}: not a G-code dialect (expected one of {})", d->first,
                       gcode::dialect_names()));
  }
  validate(m);
  return m;
}

Machine read_machine(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext == ".ini" ? read_linuxcnc_ini(file) : read_machine_toml(file);
}

std::string to_toml(const Machine& m) {
  std::string out = fmt::format("# read from {}\nname = \"{}\"\nmax_feed_mm_min = {}\nrapid_feed_mm_min = {}\n"
                                "chord_tolerance_mm = {}\npath_tolerance_mm = {}\nservo_period_s = {}\n",
                                m.source, m.name, m.max_feed_mm_s * 60.0, m.rapid_feed_mm_s * 60.0,
                                m.chord_tolerance_mm, m.path_tolerance_mm, m.servo_period_s);
  if (m.dialect) out += fmt::format("dialect = \"{}\"\n", gcode::to_string(*m.dialect));
  if (!m.subroutine_path.empty()) {
    out += "subroutine_path = [";
    for (std::size_t i = 0; i < m.subroutine_path.size(); ++i)
      out += fmt::format("{}\"{}\"", i ? ", " : "", m.subroutine_path[i]);
    out += "]\n";
  }
  if (!m.tool_table.empty()) {
    out += fmt::format("tool_table = \"{}\"\n", m.tool_table);
    if (m.tool_table_mm_per_unit != 1.0) out += "tool_table_units = \"inch\"\n";
  }
  for (const auto& a : m.axes) {
    const char* u = a.rotary ? "deg" : "mm";
    out += fmt::format("\n[axes.{}]\nmax_velocity = {}          # [{}/s]\nmax_acceleration = {}      # [{}/s^2]\n"
                       "max_jerk = {}              # [{}/s^3]\n",
                       a.name, a.max_velocity, u, a.max_acceleration, u, a.max_jerk, u);
    if (std::isfinite(a.min_position)) out += fmt::format("min_position = {}\n", a.min_position);
    if (std::isfinite(a.max_position)) out += fmt::format("max_position = {}\n", a.max_position);
  }
  return out;
}

}  // namespace kontur
