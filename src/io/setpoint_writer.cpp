#include <kontur/io/setpoint_writer.hpp>

#include <fmt/format.h>

#include <array>
#include <bit>
#include <cstring>

namespace kontur {
namespace {

static_assert(std::endian::native == std::endian::little, "the binary setpoint format is written on little-endian hosts");

template <class T>
void put(std::ostream& out, T v) {
  std::array<char, sizeof(T)> b;
  std::memcpy(b.data(), &v, sizeof(T));
  out.write(b.data(), static_cast<std::streamsize>(b.size()));
}

}  // namespace

std::uint64_t binary_setpoint_bytes(const AxisLayout& layout, std::uint64_t count) noexcept {
  const std::uint64_t header = layout == AxisLayout::xyz() ? 24 : 40;
  return header + 8 * static_cast<std::uint64_t>(layout.size() + 3) * count;
}

SetpointWriter::SetpointWriter(std::ostream& out, SetpointFormat format, double period_s, const AxisLayout& layout)
    : out_(&out), format_(format), axes_(layout.size()) {
  const bool xyz = layout == AxisLayout::xyz();
  if (format_ == SetpointFormat::csv) {
    std::string header = "t,";
    for (int i = 0; i < layout.size(); ++i) {
      header += static_cast<char>(layout.letter(i) - 'A' + 'a');
      header += ',';
    }
    *out_ << header << "v,block\n";
  } else {
    out_->write(setpoint_binary_magic, 8);
    put<std::uint32_t>(*out_, xyz ? setpoint_binary_version : setpoint_binary_version_axes);
    put<std::uint32_t>(*out_, static_cast<std::uint32_t>(8 * (layout.size() + 3)));
    put<double>(*out_, period_s);
    if (!xyz) {
      put<std::uint32_t>(*out_, static_cast<std::uint32_t>(layout.size()));
      std::array<char, 12> letters{};
      for (int i = 0; i < layout.size(); ++i) letters[static_cast<std::size_t>(i)] = layout.letter(i);
      out_->write(letters.data(), static_cast<std::streamsize>(letters.size()));
    }
  }
}

void SetpointWriter::write(const trajectory::Setpoint& s) {
  ++count_;
  if (format_ == SetpointFormat::binary) {
    put<double>(*out_, s.t_s);
    for (int i = 0; i < axes_; ++i) put<double>(*out_, s.position[i]);
    put<double>(*out_, s.v_mm_s);
    put<std::int64_t>(*out_, s.source_line);
    return;
  }
  // -0 is written as 0 so that equal runs give equal bytes. Positions in the shortest form that
  // reads back to the same double: a check of the file then sees the planner's jerk, not the
  // rounding of the file (1e-9 mm would show as 8e-9 / T^3 = 8 mm/s^3 at T = 1 ms).
  auto z = [](double v) { return v == 0.0 ? 0.0 : v; };
  fmt::memory_buffer b;
  fmt::format_to(std::back_inserter(b), "{:.9f}", z(s.t_s));
  for (int i = 0; i < axes_; ++i) fmt::format_to(std::back_inserter(b), ",{}", z(s.position[i]));
  fmt::format_to(std::back_inserter(b), ",{:.6f},{}\n", z(s.v_mm_s), s.source_line);
  out_->write(b.data(), static_cast<std::streamsize>(b.size()));
}

}  // namespace kontur
