#pragma once
// Internal: the program text as a stream of lines, read through a fixed buffer (a file) or from
// memory, with seeking back to a line start already read (for a dialect's loops and calls).
// Lines end with LF or CR LF and are limited to tolerances::gcode_max_line_length characters; a NUL
// byte anywhere means the input is not a text file. Dialect-neutral.
#include "diagnostics.hpp"

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace kontur::gcode::detail {

class ProgramInput {
public:
  /// `diagnostics` gets the current line number as lines are read.
  explicit ProgramInput(Diagnostics& diagnostics) : diag_(diagnostics) {}
  ~ProgramInput();
  ProgramInput(const ProgramInput&) = delete;
  ProgramInput& operator=(const ProgramInput&) = delete;

  /// Opens the file `path`; throws InputError if it does not exist or is not a text file.
  void open(const std::string& path);
  /// Reads from `text` (kept).
  void open_memory(std::string text);

  /// The next line without its end-of-line characters into `out` (valid until the next call);
  /// false at the end of the input. Advances the line number.
  bool read_line(std::string_view& out);
  /// Offset in the input of the next line to read.
  [[nodiscard]] std::size_t tell() const noexcept { return buffer_offset_ + begin_; }
  /// Offset in the input of the line last read.
  [[nodiscard]] std::size_t line_start() const noexcept { return line_start_; }
  /// Continues reading at `offset` (a line start seen before), as if line `line` - 1 was just read.
  void seek(std::size_t offset, long line);

private:
  const char* data() const noexcept { return file_ ? buf_.data() : memory_.data(); }
  // Reads more of the file into the buffer (keeping [begin, end)).
  void fill();
  // A NUL byte anywhere means a binary file: say so instead of reporting a syntax error.
  void check_text(std::size_t from) const;

  Diagnostics& diag_;
  std::FILE* file_ = nullptr;
  std::string memory_;
  std::vector<char> buf_;
  std::size_t begin_ = 0, end_ = 0;
  std::size_t buffer_offset_ = 0;  // bytes of the file before buf[0]
  std::size_t line_start_ = 0;
  bool input_eof_ = false;
};

}  // namespace kontur::gcode::detail
