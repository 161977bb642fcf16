/* Kontur's lower level (kontur_ll.h): the stream format is docs/segments.md. */
#include "kontur_ll.h"

/* ---------------------------------------------------------------- little-endian reading */

static uint32_t rd_u32(const uint8_t* p) {
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static uint64_t rd_u64(const uint8_t* p) { return (uint64_t)rd_u32(p) | ((uint64_t)rd_u32(p + 4) << 32); }

static int32_t rd_i32(const uint8_t* p) {
  union {
    uint32_t u;
    int32_t i;
  } v;
  v.u = rd_u32(p);
  return v.i;
}

/* A payload value, binary32 or binary64; *finite = 0 for a NaN or an infinity. */
static double rd_value(const uint8_t* p, int f32, int* finite) {
  if (f32) {
    union {
      uint32_t u;
      float f;
    } v;
    v.u = rd_u32(p);
    if (((v.u >> 23) & 0xffu) == 0xffu) *finite = 0;
    return (double)v.f;
  } else {
    union {
      uint64_t u;
      double d;
    } v;
    v.u = rd_u64(p);
    if (((v.u >> 52) & 0x7ffu) == 0x7ffu) *finite = 0;
    return v.d;
  }
}

static int finite_positive(double x) {
  union {
    double d;
    uint64_t u;
  } v;
  v.d = x;
  return ((v.u >> 52) & 0x7ffu) != 0x7ffu && x > 0.0;
}

/* ---------------------------------------------------------------- CRC-32 */

/* Half a byte at a time: a 16-entry table (64 bytes of flash) instead of 256 entries or 8 shifts. */
static const uint32_t kll_crc_nibble[16] = {
    0x00000000u, 0x1db71064u, 0x3b6e20c8u, 0x26d930acu, 0x76dc4190u, 0x6b6b51f4u, 0x4db26158u, 0x5005713cu,
    0xedb88320u, 0xf00f9344u, 0xd6d6a3e8u, 0xcb61b38cu, 0x9b64c2b0u, 0x86d3d2d4u, 0xa00ae278u, 0xbdbdf21cu};

uint32_t kll_crc32(const uint8_t* bytes, size_t n) {
  uint32_t crc = 0xffffffffu;
  size_t i;
  for (i = 0; i < n; ++i) {
    crc ^= bytes[i];
    crc = (crc >> 4) ^ kll_crc_nibble[crc & 15u];
    crc = (crc >> 4) ^ kll_crc_nibble[crc & 15u];
  }
  return crc ^ 0xffffffffu;
}

/* ---------------------------------------------------------------- header */

int kll_open(kll_stream* s, const uint8_t* header, size_t size) {
  static const char magic[8] = {'K', 'O', 'N', 'T', 'U', 'R', 'S', 'G'};
  uint32_t i, c;
  int k;
  if (size < KLL_HEADER_SIZE) return KLL_ERR_SIZE;
  for (i = 0; i < 8; ++i)
    if (header[i] != (uint8_t)magic[i]) return KLL_ERR_MAGIC;
  if (rd_u32(header + 60) != kll_crc32(header, 60)) return KLL_ERR_CHECKSUM;
  if (rd_u32(header + 8) != KLL_FORMAT_VERSION) return KLL_ERR_VERSION;
  s->header.version = rd_u32(header + 8);
  s->header.axes = rd_u32(header + 12);
  if (s->header.axes < 1u || s->header.axes > (uint32_t)KLL_MAX_AXES) return KLL_ERR_FORMAT;
  for (i = 0; i < 12; ++i) s->header.letters[i] = (char)header[16 + i];
  {
    int finite = 1;
    s->header.period_s = rd_value(header + 32, 0, &finite);
    s->header.tolerance_mm = rd_value(header + 40, 0, &finite);
    s->header.speed_tolerance_mm_s = rd_value(header + 48, 0, &finite);
    if (!finite || !finite_positive(s->header.period_s) || !finite_positive(s->header.tolerance_mm) ||
        !finite_positive(s->header.speed_tolerance_mm_s))
      return KLL_ERR_FORMAT;
  }
  s->channels = s->header.axes + 1u;
  s->next_index = 0;
  s->remaining = 0;
  s->given = 0;
  s->degree = 0;
  s->mark_count = 0;
  s->next_mark = 0;
  s->line = 0;
  s->ended = 0;
  s->cycle = 0;
  for (c = 0; c < (uint32_t)KLL_MAX_CHANNELS; ++c)
    for (k = 0; k <= KLL_MAX_DEGREE; ++k) s->d[c][k] = 0.0;
  return KLL_OK;
}

/* ---------------------------------------------------------------- records */

static uint32_t rd_u16(const uint8_t* p) { return (uint32_t)p[0] | ((uint32_t)p[1] << 8); }

/* An unsigned LEB128 varint of at most 5 bytes at p[*at], p[limit] the first byte past the
 * record's marks; 0 if it runs past or is too long. */
static int rd_varint(const uint8_t* p, size_t limit, size_t* at, uint32_t* value) {
  uint32_t v = 0;
  int shift;
  for (shift = 0; shift < 35; shift += 7) {
    uint8_t b;
    if (*at >= limit) return 0;
    b = p[(*at)++];
    v |= (uint32_t)(b & 0x7fu) << shift;
    if ((b & 0x80u) == 0u) {
      *value = v;
      return 1;
    }
  }
  return 0;
}

int kll_record_size(const uint8_t* head, size_t size, size_t* record_size) {
  uint32_t n;
  if (size < KLL_RECORD_HEAD_SIZE) return KLL_ERR_SIZE;
  n = rd_u16(head + 8);
  if (n < KLL_RECORD_HEAD_SIZE + 4u || n > KLL_MAX_RECORD_SIZE) return KLL_ERR_FORMAT;
  *record_size = n;
  return KLL_OK;
}

/* Forward differences at m = 0 of m^j (j = 3, 4, 5), orders 0..5: k! S(j, k). */
static const double kll_power_differences[3][KLL_MAX_DEGREE + 1] = {
    {0.0, 1.0, 6.0, 6.0, 0.0, 0.0},
    {0.0, 1.0, 14.0, 36.0, 24.0, 0.0},
    {0.0, 1.0, 30.0, 150.0, 240.0, 120.0},
};

int kll_feed(kll_stream* s, const uint8_t* record, size_t size) {
  size_t need = 0, at;
  uint32_t kind, degree, flags, width, marks, cycles, mask, i, c, per_channel, nvalues = 0;
  uint32_t offsets[KLL_MAX_MARKS];
  int32_t lines[KLL_MAX_MARKS];
  int32_t line;
  int r, k, finite = 1;
  double values[KLL_MAX_CHANNELS * (KLL_MAX_DEGREE + 1)];
  if (s->ended || s->remaining != 0u) return KLL_ERR_STATE;
  r = kll_record_size(record, size, &need);
  if (r != KLL_OK) return r;
  if (size < need) return KLL_ERR_SIZE;
  if (rd_u32(record + need - 4u) != kll_crc32(record, need - 4u)) return KLL_ERR_CHECKSUM;
  if (rd_u16(record + 6) != (s->next_index & 0xffffu)) return KLL_ERR_INDEX;
  kind = record[0];
  degree = record[1];
  flags = record[2];
  marks = record[3];
  cycles = rd_u16(record + 4);
  mask = rd_u16(record + 10);
  if (kind < KLL_KIND_ANCHOR || kind > KLL_KIND_END || degree > (uint32_t)KLL_MAX_DEGREE ||
      (flags & ~(KLL_FLAG_FLOAT32 | KLL_FLAG_LINE)) != 0u || marks > (uint32_t)KLL_MAX_MARKS ||
      (mask >> s->channels) != 0u)
    return KLL_ERR_FORMAT;
  at = KLL_RECORD_HEAD_SIZE;
  if (kind == KLL_KIND_END) {
    if (cycles != 0u || marks != 0u || degree != 0u || flags != 0u || mask != 0u ||
        need != KLL_RECORD_HEAD_SIZE + 8u + 4u)
      return KLL_ERR_FORMAT;
    if (rd_u64(record + at) != s->cycle) return KLL_ERR_COUNT;
    s->ended = 1;
    s->next_index += 1u;
    return KLL_OK;
  }
  if (cycles == 0u) return KLL_ERR_FORMAT;
  /* A continuation needs a state to continue; an anchor sets every channel. */
  if (kind == KLL_KIND_CONTINUE && s->next_index == 0u) return KLL_ERR_FORMAT;
  if (kind == KLL_KIND_ANCHOR && mask != (1u << s->channels) - 1u) return KLL_ERR_FORMAT;
  line = s->line;
  if (flags & KLL_FLAG_LINE) {
    if (need < at + 4u) return KLL_ERR_FORMAT;
    line = rd_i32(record + at);
    at += 4u;
  }
  /* The marks: offsets strictly increasing inside the piece, lines by zigzag steps. */
  {
    uint32_t offset = 0, step, zig;
    int32_t mark_line = line;
    for (i = 0; i < marks; ++i) {
      if (!rd_varint(record, need - 4u, &at, &step) || !rd_varint(record, need - 4u, &at, &zig)) return KLL_ERR_FORMAT;
      if (step == 0u || step >= cycles - offset) return KLL_ERR_FORMAT;
      offset += step;
      mark_line = (int32_t)((uint32_t)mark_line + ((zig >> 1) ^ (0u - (zig & 1u))));
      offsets[i] = offset;
      lines[i] = mark_line;
    }
  }
  /* The values: every channel of the mask, (degree + 1) for an anchor, (degree - 2) to continue. */
  per_channel = kind == KLL_KIND_ANCHOR ? degree + 1u : (degree > 2u ? degree - 2u : 0u);
  for (c = 0; c < s->channels; ++c)
    if (mask & (1u << c)) nvalues += per_channel;
  width = (flags & KLL_FLAG_FLOAT32) ? 4u : 8u;
  if (need != at + width * nvalues + 4u) return KLL_ERR_FORMAT;
  for (i = 0; i < nvalues; ++i) {
    values[i] = rd_value(record + at + width * i, width == 4u, &finite);
    if (!(values[i] <= KLL_MAX_VALUE && values[i] >= -KLL_MAX_VALUE)) finite = 0;
  }
  if (!finite) return KLL_ERR_NOT_FINITE;
  /* Valid: apply. */
  for (i = 0; i < marks; ++i) {
    s->mark_offset[i] = offsets[i];
    s->mark_line[i] = lines[i];
  }
  s->mark_count = marks;
  s->next_mark = 0;
  s->line = line;
  if (kind == KLL_KIND_ANCHOR) {
    for (c = 0; c < s->channels; ++c)
      for (k = 0; k <= KLL_MAX_DEGREE; ++k)
        s->d[c][k] = (uint32_t)k <= degree ? values[c * (degree + 1u) + (uint32_t)k] : 0.0;
    s->degree = degree;
  } else if (per_channel > 0u) {
    /* The same polynomial continued, plus dc_j m^j for j = 3..degree: its differences change by
     * dc_j times those of m^j. */
    const double* dc = values;
    uint32_t j;
    for (c = 0; c < s->channels; ++c) {
      if (!(mask & (1u << c))) continue;
      for (k = 1; k <= KLL_MAX_DEGREE; ++k) {
        double delta = 0.0;
        for (j = 0; j < per_channel; ++j) delta += kll_power_differences[j][k] * dc[j];
        s->d[c][k] += delta;
      }
      dc += per_channel;
    }
    if (degree > s->degree) s->degree = degree;
  }
  s->remaining = cycles;
  s->given = 0;
  s->next_index += 1u;
  return KLL_OK;
}

/* ---------------------------------------------------------------- the cycle */

int kll_next(kll_stream* s, kll_setpoint* out) {
  uint32_t c, n = s->header.axes, p = s->degree;
  uint32_t k;
  if (s->remaining == 0u) return s->ended ? KLL_END : KLL_NEED_PIECE;
  while (s->next_mark < s->mark_count && s->mark_offset[s->next_mark] == s->given) {
    s->line = s->mark_line[s->next_mark];
    s->next_mark += 1u;
  }
  out->cycle = s->cycle;
  for (c = 0; c < (uint32_t)KLL_MAX_AXES; ++c) out->position[c] = c < n ? s->d[c][0] : 0.0;
  out->speed_mm_s = s->d[n][0];
  out->line = s->line;
  /* p additions per channel: D_k += D_(k+1), lowest order first (each takes the old D_(k+1)). */
  for (c = 0; c < s->channels; ++c) {
    double* d = s->d[c];
    for (k = 0; k < p; ++k) d[k] += d[k + 1u];
  }
  s->given += 1u;
  s->remaining -= 1u;
  s->cycle += 1u;
  return KLL_SETPOINT;
}
