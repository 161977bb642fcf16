#include <fmt/format.h>

#include <array>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <kontur/error.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/io/setpoint_writer.hpp>
#include <kontur/segments/segment_stream.hpp>
#include <optional>
#include <string_view>

namespace kontur {
namespace {

template <class T>
T get(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// The layout named by letters in a file (upper or lower case), or InputError naming the file.
AxisLayout file_layout(const std::string& letters, const std::string& path, const std::string& where) {
  std::string upper;
  for (const char c : letters) upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  static constexpr std::string_view order = "XYZABCUVW";
  bool ordered = upper.size() >= 3 && upper.substr(0, 3) == "XYZ";
  for (std::size_t i = 1; i < upper.size() && ordered; ++i)
    ordered = order.find(upper[i - 1]) < order.find(upper[i]) && order.find(upper[i]) != std::string_view::npos;
  if (!ordered)
    throw InputError("setpoints-axes",
                     fmt::format("{}: {} names the axes \"{}\": a setpoint file has x y z, then any of a b c u v w "
                                 "in that order",
                                 path, where, letters));
  return AxisLayout::from_letters(upper);
}

SetpointHeader read_binary(std::ifstream& in, const std::string& path, const SetpointVisitor& visit,
                           const HeaderVisitor& on_header) {
  std::array<char, 24> h{};
  in.read(h.data(), 24);
  if (in.gcount() != 24)
    throw InputError("setpoints-truncated",
                     fmt::format("{}: the binary header is cut short (24 bytes expected)", path));
  const auto version = get<std::uint32_t>(h.data() + 8), size = get<std::uint32_t>(h.data() + 12);
  SetpointHeader header;
  header.period_s = get<double>(h.data() + 16);
  if (version == setpoint_binary_version_axes) {
    std::array<char, 16> a{};
    in.read(a.data(), 16);
    if (in.gcount() != 16)
      throw InputError("setpoints-truncated",
                       fmt::format("{}: the binary header of version 2 is cut short (40 bytes expected)", path));
    const auto n = get<std::uint32_t>(a.data());
    if (n < 3 || n > static_cast<std::uint32_t>(max_axes))
      throw InputError("setpoints-axes", fmt::format("{}: the header gives {} axes: 3 to {} expected", path, n, max_axes));
    header.layout = file_layout(std::string(a.data() + 4, n), path, "the header");
  } else if (version != setpoint_binary_version) {
    throw InputError("setpoints-version", fmt::format("{}: binary setpoints version {}: this Kontur reads versions {} "
                                                      "and {}",
                                                      path, version, setpoint_binary_version,
                                                      setpoint_binary_version_axes));
  }
  const int n = header.layout.size();
  const auto record = static_cast<std::uint32_t>(8 * (n + 3));
  if (size != record)
    throw InputError("setpoints-version", fmt::format("{}: binary setpoints version {} with records of {} bytes: "
                                                      "{} axes take records of {} bytes",
                                                      path, version, size, n, record));
  if (on_header) on_header(header);
  trajectory::Setpoint sp;
  sp.position = AxisVector::Zero(n);
  std::array<char, 8 * (max_axes + 3)> r{};
  for (long k = 0;; ++k) {
    in.read(r.data(), record);
    if (in.gcount() == 0) break;
    if (in.gcount() != record)
      throw InputError("setpoints-truncated",
                       fmt::format("{}: record {} is cut short ({} of {} bytes)", path, k + 1, in.gcount(), record));
    sp.t_s = get<double>(r.data());
    for (int i = 0; i < n; ++i) sp.position[i] = get<double>(r.data() + 8 * (i + 1));
    sp.v_mm_s = get<double>(r.data() + 8 * (n + 1));
    sp.source_line = static_cast<long>(get<std::int64_t>(r.data() + 8 * (n + 2)));
    visit(sp);
  }
  return header;
}

SetpointHeader read_csv(std::ifstream& in, const std::string& path, const SetpointVisitor& visit,
                        const HeaderVisitor& on_header) {
  trajectory::Setpoint sp;
  std::string line;
  long n = 1;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  // t, the axes (one letter each), v, block
  std::string letters;
  bool shaped = line.size() >= 2 && line.substr(0, 2) == "t," && line.size() >= 8 &&
                line.substr(line.size() - 8) == ",v,block";
  if (shaped) {
    const std::string middle = line.substr(2, line.size() - 10);
    for (std::size_t i = 0; i < middle.size() && shaped; ++i) {
      if (i % 2 == 1) shaped = middle[i] == ',';
      else letters += middle[i];
    }
    shaped = shaped && middle.size() % 2 == 1;
  }
  if (!shaped)
    throw InputError("setpoints-header",
                     fmt::format("{}:1: the header is \"{}\": a setpoint CSV starts with \"t,x,y,z,v,block\" (or "
                                 "with more axes, \"t,x,y,z,a,v,block\")",
                                 path, line.substr(0, 60)));
  SetpointHeader header;
  header.layout = file_layout(letters, path, "the header (line 1)");
  if (on_header) on_header(header);
  const int axes = header.layout.size();
  const int columns = axes + 3;
  sp.position = AxisVector::Zero(axes);
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::array<double, max_axes + 2> v{};
    long block = 0;
    const char* p = line.data();
    const char* end = line.data() + line.size();
    for (int c = 0; c < columns; ++c) {
      const bool last = c == columns - 1;
      const char* q = static_cast<const char*>(std::memchr(p, ',', static_cast<std::size_t>(end - p)));
      const char* field_end = !last ? (q ? q : end) : end;
      std::from_chars_result res{};
      if (!last)
        res = std::from_chars(p, field_end, v[static_cast<std::size_t>(c)]);
      else
        res = std::from_chars(p, field_end, block);
      if (res.ec != std::errc() || res.ptr != field_end || (!last && !q))
        throw InputError("setpoints-row",
                         fmt::format("{}:{}: column {} of \"{}\" is not a number: a row holds t, the {} axes, v "
                                     "(numbers) and block (an integer)",
                                     path, n, c + 1, line.substr(0, 80), axes));
      p = field_end + 1;
    }
    sp.t_s = v[0];
    for (int i = 0; i < axes; ++i) sp.position[i] = v[static_cast<std::size_t>(i + 1)];
    sp.v_mm_s = v[static_cast<std::size_t>(axes + 1)];
    sp.source_line = block;
    visit(sp);
  }
  return header;
}

}  // namespace

SetpointHeader for_each_setpoint(const std::string& path, const SetpointVisitor& visit, const HeaderVisitor& header) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("file-missing", fmt::format("{}: cannot open the setpoint file", path));
  std::array<char, 8> magic{};
  in.read(magic.data(), 8);
  const bool binary =
      in.gcount() == 8 && std::string_view(magic.data(), 8) == std::string_view(setpoint_binary_magic, 8);
  const bool stream =
      in.gcount() == 8 && std::string_view(magic.data(), 8) == std::string_view(segments::segment_stream_magic, 8);
  in.clear();
  in.seekg(0);
  if (stream) {
    // A segment stream: the lower level makes its setpoints (docs/segments.md).
    SetpointHeader h;
    segments::replay_segments(
        in, path,
        [&](const segments::SegmentHeader& sh) {
          h.period_s = sh.period_s;
          h.layout = sh.layout;
          if (header) header(h);
        },
        visit);
    return h;
  }
  return binary ? read_binary(in, path, visit, header) : read_csv(in, path, visit, header);
}

SetpointFile read_setpoints(const std::string& path) {
  SetpointFile f;
  const SetpointHeader h = for_each_setpoint(path, [&](const trajectory::Setpoint& s) { f.samples.push_back(s); });
  f.period_s = h.period_s;
  f.layout = h.layout;
  return f;
}

}  // namespace kontur
