#pragma once
// Internal: the program text as a stream of lines, read through a fixed buffer (a file) or from
// memory, with seeking back to a line start already read (for a dialect's loops and calls), and
// further files (subroutines in files of their own, add_file) read whole into memory, each in an
// offset range of its own: an offset names the file and the place, so a call and its return are
// one seek each.
// Lines end with LF or CR LF and are limited to tolerances::gcode_max_line_length characters; a NUL
// byte anywhere means the input is not a text file. Dialect-neutral.
#include "diagnostics.hpp"

#include <cstddef>
#include <cstdio>
#include <memory>
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
  [[nodiscard]] std::size_t tell() const noexcept {
    return current_ ? (current_ << added_shift) + added_pos_ : buffer_offset_ + begin_;
  }
  /// Offset in the input of the line last read.
  [[nodiscard]] std::size_t line_start() const noexcept { return line_start_; }
  /// Continues reading at `offset` (a line start seen before, or a file's first_offset), as if line
  /// `line` - 1 was just read; messages name the file the offset is in.
  void seek(std::size_t offset, long line);

  /// Adds the file `path` (a subroutine file, read whole, at most
  /// tolerances::gcode_max_subroutine_file_bytes) and returns the offset of its first line; the
  /// same path twice gives the same offset. Throws InputError if it cannot be read or is not text.
  std::size_t add_file(const std::string& path);

private:
  const char* data() const noexcept { return file_ ? buf_.data() : memory_.data(); }
  // Reads more of the file into the buffer (keeping [begin, end)).
  void fill();
  // A NUL byte anywhere means a binary file: say so instead of reporting a syntax error.
  void check_text(std::size_t from) const;

  // A file added by add_file: its name (for messages and blocks) and its text.
  struct Added {
    std::string path;
    std::shared_ptr<const std::string> name;
    std::string text;
  };
  static constexpr int added_shift = 40;  // added file k (1-based) holds offsets [k << 40, (k + 1) << 40)
  bool read_added_line(std::string_view& out);

  Diagnostics& diag_;
  std::shared_ptr<const std::string> main_name_;  // the program's name, for seeking back into it
  std::vector<Added> added_;
  std::size_t current_ = 0;   // 0: the program; k: added_[k - 1]
  std::size_t added_pos_ = 0; // position in added_[current_ - 1].text
  std::FILE* file_ = nullptr;
  std::string memory_;
  std::vector<char> buf_;
  std::size_t begin_ = 0, end_ = 0;
  std::size_t buffer_offset_ = 0;  // bytes of the file before buf[0]
  std::size_t line_start_ = 0;
  bool input_eof_ = false;
};

}  // namespace kontur::gcode::detail
