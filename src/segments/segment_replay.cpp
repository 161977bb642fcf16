// The lower level on the host: replays a segment stream (segments/segment_stream.hpp) with the C
// library a controller would run (lower_level/kontur_ll.c).
#include <fmt/format.h>

#include <array>
#include <kontur/error.hpp>
#include <kontur/segments/segment_stream.hpp>
#include <string>

#include "kontur_ll.h"
#include "segment_bytes.hpp"

namespace kontur::segments {
namespace {

const char* describe(int result) {
  switch (result) {
    case KLL_ERR_MAGIC: return "it does not start with KONTURSG: not a segment stream";
    case KLL_ERR_VERSION: return "its format version is not 1, the one this replay reads";
    case KLL_ERR_CHECKSUM: return "its CRC-32 does not match its bytes: the stream is damaged";
    case KLL_ERR_INDEX: return "its index is not the next one: a piece was lost, repeated or reordered";
    case KLL_ERR_FORMAT: return "a field is out of range (kind, degree, flags, line marks, cycle count or axis count)";
    case KLL_ERR_SIZE: return "it is cut short";
    case KLL_ERR_STATE: return "it comes after the end record";
    case KLL_ERR_COUNT: return "the end record's setpoint count differs from the setpoints the pieces make";
    case KLL_ERR_NOT_FINITE: return "a coefficient is a NaN, an infinity or beyond 1e12";
    default: return "it cannot be read";
  }
}

}  // namespace

SegmentStats replay_segments(std::istream& in, const std::string& name,
                             const std::function<void(const SegmentHeader&)>& header,
                             const std::function<void(const trajectory::Setpoint&)>& visit) {
  SegmentStats stats;
  std::array<std::uint8_t, KLL_HEADER_SIZE> h{};
  in.read(reinterpret_cast<char*>(h.data()), h.size());
  const auto got = static_cast<std::size_t>(in.gcount());
  kll_stream s{};
  const int opened = kll_open(&s, h.data(), got);
  if (opened != KLL_OK)
    throw InputError("segments-header", fmt::format("{}: the header ({} bytes): {}", name, got,
                                                    opened == KLL_ERR_SIZE ? "cut short (64 bytes expected)" : describe(opened)));
  SegmentHeader head;
  std::string letters;
  for (std::uint32_t i = 0; i < s.header.axes; ++i) letters += s.header.letters[i];
  try {
    head.layout = AxisLayout::from_letters(letters);
  } catch (const InputError&) {
    throw InputError("segments-header", fmt::format("{}: the header names the axes \"{}\"", name, letters));
  }
  head.period_s = s.header.period_s;
  head.tolerance_mm = s.header.tolerance_mm;
  head.speed_tolerance_mm_s = s.header.speed_tolerance_mm_s;
  if (header) header(head);
  stats.bytes = KLL_HEADER_SIZE;
  std::array<std::uint8_t, KLL_MAX_RECORD_SIZE> record{};
  kll_setpoint sp;
  trajectory::Setpoint out;
  out.position = AxisVector::Zero(head.layout.size());
  const trajectory::ServoClock clock(head.period_s);
  for (;;) {
    const int r = kll_next(&s, &sp);
    if (r == KLL_SETPOINT) {
      out.t_s = clock.time_s(static_cast<long>(sp.cycle));  // as the sampler
      for (int i = 0; i < head.layout.size(); ++i) out.position[i] = sp.position[static_cast<std::size_t>(i)];
      out.v_mm_s = sp.speed_mm_s;
      out.source_line = sp.line;
      ++stats.setpoints;
      if (visit) visit(out);
      continue;
    }
    if (r == KLL_END) break;
    // The next record: its head, then the rest.
    const std::uint64_t offset = stats.bytes;
    const std::uint32_t piece = s.next_index;
    auto refuse = [&](const std::string& why) {
      throw InputError("segments-damaged", fmt::format("{}: piece {} (byte {}): {}; nothing after piece {} is replayed",
                                                       name, piece, offset, why, static_cast<long>(piece) - 1));
    };
    in.read(reinterpret_cast<char*>(record.data()), KLL_RECORD_HEAD_SIZE);
    if (in.gcount() == 0) refuse("the stream ends here, without its end record");
    if (static_cast<std::size_t>(in.gcount()) < KLL_RECORD_HEAD_SIZE) refuse(describe(KLL_ERR_SIZE));
    std::size_t size = 0;
    if (const int e = kll_record_size(record.data(), KLL_RECORD_HEAD_SIZE, &size); e != KLL_OK) refuse(describe(e));
    in.read(reinterpret_cast<char*>(record.data() + KLL_RECORD_HEAD_SIZE),
            static_cast<std::streamsize>(size - KLL_RECORD_HEAD_SIZE));
    if (static_cast<std::size_t>(in.gcount()) != size - KLL_RECORD_HEAD_SIZE) refuse(describe(KLL_ERR_SIZE));
    if (const int e = kll_feed(&s, record.data(), size); e != KLL_OK) refuse(describe(e));
    stats.bytes += size;
    if (record[0] == KLL_KIND_END) continue;
    ++stats.pieces;
    if (record[0] == KLL_KIND_ANCHOR) ++stats.anchors;
    if ((record[2] & KLL_FLAG_FLOAT32) != 0) ++stats.float32_pieces;
    ++stats.by_degree[record[1]];
  }
  if (in.peek() != std::char_traits<char>::eof())
    throw InputError("segments-damaged",
                     fmt::format("{}: bytes follow the end record at byte {}: the stream is damaged", name, stats.bytes));
  return stats;
}

}  // namespace kontur::segments
