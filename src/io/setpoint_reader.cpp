#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <kontur/error.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/io/setpoint_writer.hpp>
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

std::optional<double> read_binary(std::ifstream& in, const std::string& path, const SetpointVisitor& visit,
                                  const PeriodVisitor& period) {
  std::array<char, 24> h{};
  in.read(h.data(), 24);
  if (in.gcount() != 24)
    throw InputError("setpoints-truncated",
                     fmt::format("{}: the binary header is cut short (24 bytes expected)", path));
  const auto version = get<std::uint32_t>(h.data() + 8), size = get<std::uint32_t>(h.data() + 12);
  if (version != setpoint_binary_version || size != 48)
    throw InputError("setpoints-version", fmt::format("{}: binary setpoints version {} with records of {} bytes: "
                                                      "this Kontur reads version {} with 48-byte records",
                                                      path, version, size, setpoint_binary_version));
  const double period_s = get<double>(h.data() + 16);
  if (period) period(period_s);
  trajectory::Setpoint sp;
  std::array<char, 48> r{};
  for (long k = 0;; ++k) {
    in.read(r.data(), 48);
    if (in.gcount() == 0) break;
    if (in.gcount() != 48)
      throw InputError("setpoints-truncated",
                       fmt::format("{}: record {} is cut short ({} of 48 bytes)", path, k + 1, in.gcount()));
    sp.t_s = get<double>(r.data());
    sp.position = AxisVector(Vec3(get<double>(r.data() + 8), get<double>(r.data() + 16), get<double>(r.data() + 24)));
    sp.v_mm_s = get<double>(r.data() + 32);
    sp.source_line = static_cast<long>(get<std::int64_t>(r.data() + 40));
    visit(sp);
  }
  return period_s;
}

std::optional<double> read_csv(std::ifstream& in, const std::string& path, const SetpointVisitor& visit) {
  trajectory::Setpoint sp;
  std::string line;
  long n = 1;
  if (!std::getline(in, line) || (line != "t,x,y,z,v,block" && line != "t,x,y,z,v,block\r"))
    throw InputError("setpoints-header",
                     fmt::format("{}:1: the header is \"{}\": a setpoint CSV starts with \"t,x,y,z,v,block\"", path,
                                 line.substr(0, 60)));
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::array<double, 5> v{};
    long block = 0;
    const char* p = line.data();
    const char* end = line.data() + line.size();
    for (int c = 0; c < 6; ++c) {
      const char* q = static_cast<const char*>(std::memchr(p, ',', static_cast<std::size_t>(end - p)));
      const char* field_end = c < 5 ? (q ? q : end) : end;
      std::from_chars_result res{};
      if (c < 5)
        res = std::from_chars(p, field_end, v[static_cast<std::size_t>(c)]);
      else
        res = std::from_chars(p, field_end, block);
      if (res.ec != std::errc() || res.ptr != field_end || (c < 5 && !q))
        throw InputError("setpoints-row",
                         fmt::format("{}:{}: column {} of \"{}\" is not a number: a row holds t, x, y, z, v "
                                     "(numbers) and block (an integer)",
                                     path, n, c + 1, line.substr(0, 80)));
      p = field_end + 1;
    }
    sp.t_s = v[0];
    sp.position = AxisVector(Vec3(v[1], v[2], v[3]));
    sp.v_mm_s = v[4];
    sp.source_line = block;
    visit(sp);
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> for_each_setpoint(const std::string& path, const SetpointVisitor& visit,
                                        const PeriodVisitor& period) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("file-missing", fmt::format("{}: cannot open the setpoint file", path));
  std::array<char, 8> magic{};
  in.read(magic.data(), 8);
  const bool binary =
      in.gcount() == 8 && std::string_view(magic.data(), 8) == std::string_view(setpoint_binary_magic, 8);
  in.clear();
  in.seekg(0);
  return binary ? read_binary(in, path, visit, period) : read_csv(in, path, visit);
}

SetpointFile read_setpoints(const std::string& path) {
  SetpointFile f;
  f.period_s = for_each_setpoint(path, [&](const trajectory::Setpoint& s) { f.samples.push_back(s); });
  return f;
}

}  // namespace kontur
