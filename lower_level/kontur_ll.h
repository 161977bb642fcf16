/* Kontur's lower level: replays a segment stream (docs/segments.md) one setpoint per call, by
 * forward differences (seed 002, ../shared/spec/methods.md section 1): p additions per channel and
 * servo cycle, nothing else in the cycle.
 *
 * Freestanding C99: no heap, no libm, no standard I/O, no string functions; fixed-size state (one
 * kll_stream). Fed piece by piece, so a serial link or a ring buffer can feed it: the caller reads
 * the stream's 64-byte header, then each record's 16-byte head, asks kll_record_size() for the rest,
 * and hands the whole record to kll_feed() when kll_next() says it needs one.
 *
 * Exactness: every value is an IEEE 754 double added in a fixed order; the upper level (Kontur's
 * segment writer) runs this very code to choose each piece, so what a receiver makes is, bit for
 * bit, what the writer checked against the planner's setpoints. Build it with -ffp-contract=off
 * (no fused multiply-add), as lower_level/CMakeLists.txt does.
 */
#ifndef KONTUR_LL_H
#define KONTUR_LL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define KLL_FORMAT_VERSION 1u
#define KLL_MAX_AXES 9                       /* X Y Z A B C U V W */
#define KLL_MAX_CHANNELS (KLL_MAX_AXES + 1)  /* the axes, then the path speed */
#define KLL_MAX_DEGREE 5                     /* quintic pieces */
#define KLL_MAX_MARKS 64                     /* source-line changes inside one piece */
#define KLL_HEADER_SIZE 64u                  /* bytes of the stream header */
#define KLL_RECORD_HEAD_SIZE 12u             /* bytes of a record's fixed head (it gives the record's size) */
/* The largest record: head, line, marks (two varints of at most 5 bytes each), an anchor of every
 * channel at the largest degree, checksum. */
#define KLL_MAX_RECORD_SIZE \
  (KLL_RECORD_HEAD_SIZE + 4u + 10u * KLL_MAX_MARKS + 8u * KLL_MAX_CHANNELS * (KLL_MAX_DEGREE + 1) + 4u)

/* The largest magnitude of a value in a record ([mm], [deg], [mm/s] or their differences): with it
 * no piece of at most 65535 cycles can overflow a double. */
#define KLL_MAX_VALUE 1e12

/* Record kinds (byte 0 of a record). */
#define KLL_KIND_ANCHOR 1u   /* new forward differences D0..Dp for every channel */
#define KLL_KIND_CONTINUE 2u /* the same position, velocity and acceleration; new 3rd..pth coefficients */
#define KLL_KIND_END 3u      /* no piece follows; carries the number of setpoints of the stream */
/* Record flags (byte 2). */
#define KLL_FLAG_FLOAT32 1u /* payload values are IEEE 754 binary32, else binary64 */
#define KLL_FLAG_LINE 2u    /* an i32 source line for the piece's first setpoint follows the head */

/* Results. Errors are negative; kll_feed() leaves the state unchanged on an error. */
enum kll_result {
  KLL_OK = 0,
  KLL_SETPOINT = 1,   /* kll_next(): a setpoint was written */
  KLL_NEED_PIECE = 2, /* kll_next(): the current piece is used up: feed the next record */
  KLL_END = 3,        /* kll_next(): the stream ended; every setpoint was given */
  KLL_ERR_MAGIC = -1,     /* not a segment stream */
  KLL_ERR_VERSION = -2,   /* a format version this library does not read */
  KLL_ERR_CHECKSUM = -3,  /* the header's or a record's CRC-32 does not match: damaged */
  KLL_ERR_INDEX = -4,     /* a record out of order (lost, repeated or reordered) */
  KLL_ERR_FORMAT = -5,    /* a field out of range (kind, degree, flags, marks, cycles, channels) */
  KLL_ERR_SIZE = -6,      /* fewer bytes than the record or header needs */
  KLL_ERR_STATE = -7,     /* a record fed while the current piece still has setpoints, or after the end */
  KLL_ERR_COUNT = -8,     /* the end record's setpoint count differs from the setpoints given */
  KLL_ERR_NOT_FINITE = -9 /* a value is a NaN, an infinity or larger than KLL_MAX_VALUE */
};

/* The stream header, as read. */
typedef struct {
  uint32_t version;             /* format version */
  uint32_t axes;                /* number of axes n (1..9); channels = n + 1 */
  char letters[12];             /* axis letters in order, upper case, zero-padded */
  double period_s;              /* servo period [s] */
  double tolerance_mm;          /* largest distance of a replayed position from the planner's [mm] ([deg]) */
  double speed_tolerance_mm_s;  /* the same for the path speed [mm/s] */
} kll_header;

/* One setpoint. */
typedef struct {
  uint64_t cycle;                /* servo cycle, from 0 (time = cycle * period) */
  double position[KLL_MAX_AXES]; /* axis positions in the header's order [mm] or [deg] */
  double speed_mm_s;             /* planned path speed [mm/s] */
  int32_t line;                  /* source line of the block it lies on */
} kll_setpoint;

/* The whole state: fixed size, no pointers into the caller's buffers. */
typedef struct {
  kll_header header;
  uint32_t channels;    /* header.axes + 1 */
  uint32_t next_index;  /* index of the next record (it carries the low 16 bits) */
  uint32_t remaining;   /* setpoints left in the current piece */
  uint32_t given;       /* setpoints given from the current piece */
  uint32_t degree;      /* highest non-zero difference order in the state */
  uint32_t mark_count, next_mark;
  uint32_t mark_offset[KLL_MAX_MARKS];
  int32_t mark_line[KLL_MAX_MARKS];
  int32_t line;
  int ended;            /* the end record was fed */
  uint64_t cycle;       /* setpoints given in all */
  double d[KLL_MAX_CHANNELS][KLL_MAX_DEGREE + 1]; /* D0..D5 per channel at the next setpoint */
} kll_stream;

/* CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of n bytes. */
uint32_t kll_crc32(const uint8_t* bytes, size_t n);

/* Reads the 64-byte header and starts the state. */
int kll_open(kll_stream* s, const uint8_t* header, size_t size);

/* Size in bytes of the record whose first KLL_RECORD_HEAD_SIZE bytes are `head` (its field at
 * byte 8, checked against the largest record). */
int kll_record_size(const uint8_t* head, size_t size, size_t* record_size);

/* Loads the next record (whole, `size` bytes) once kll_next() returned KLL_NEED_PIECE (or before
 * the first kll_next()). Checks its CRC-32, its index, its fields. */
int kll_feed(kll_stream* s, const uint8_t* record, size_t size);

/* The next setpoint: KLL_SETPOINT (written to *out), KLL_NEED_PIECE or KLL_END. */
int kll_next(kll_stream* s, kll_setpoint* out);

#ifdef __cplusplus
}
#endif

#endif /* KONTUR_LL_H */
