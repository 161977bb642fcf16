#include "program_input.hpp"

#include <kontur/tolerances.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>

namespace kontur::gcode::detail {
namespace {
constexpr std::size_t read_chunk = 1 << 20;  // bytes read from the file at a time
}

ProgramInput::~ProgramInput() {
  if (file_) std::fclose(file_);
}

void ProgramInput::open(const std::string& path) {
  main_name_ = diag_.name();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError("file", fmt::format("{}: no such file", path));
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("file", fmt::format("{}: not a regular file", path));
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw InputError("file", fmt::format("{}: cannot be opened", path));
  buf_.resize(read_chunk);
  fill();
  check_text(0);
}

void ProgramInput::open_memory(std::string text) {
  main_name_ = diag_.name();
  memory_ = std::move(text);
  end_ = memory_.size();
  input_eof_ = true;
  check_text(0);
}

void ProgramInput::fill() {
  if (input_eof_ || !file_) return;
  if (begin_ > 0) {
    std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
    buffer_offset_ += begin_;
    end_ -= begin_;
    begin_ = 0;
  }
  const std::size_t got = std::fread(buf_.data() + end_, 1, buf_.size() - end_, file_);
  const std::size_t old_end = end_;
  end_ += got;
  if (got == 0) input_eof_ = true;
  check_text(old_end);
}

void ProgramInput::check_text(std::size_t from) const {
  const char* d = data();
  const void* z = std::memchr(d + from, 0, end_ - from);
  if (z) {
    const auto offset = buffer_offset_ + static_cast<std::size_t>(static_cast<const char*>(z) - d);
    throw InputError("not-text", fmt::format("{}: not a text file (NUL byte at offset {})", *diag_.name(), offset));
  }
}

std::size_t ProgramInput::add_file(const std::string& path) {
  for (std::size_t k = 0; k < added_.size(); ++k)
    if (added_[k].path == path) return (k + 1) << added_shift;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || !std::filesystem::is_regular_file(path, ec))
    throw InputError("file", fmt::format("{}: cannot be read", path));
  if (size > tolerances::gcode_max_subroutine_file_bytes)
    throw InputError("file", fmt::format("{}: {} bytes, more than the {} a subroutine file may have", path, size,
                                         tolerances::gcode_max_subroutine_file_bytes));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError("file", fmt::format("{}: cannot be opened", path));
  std::string text(size, '\0');
  const std::size_t got = std::fread(text.data(), 1, text.size(), f);
  std::fclose(f);
  text.resize(got);
  if (const void* z = std::memchr(text.data(), 0, text.size()))
    throw InputError("not-text", fmt::format("{}: not a text file (NUL byte at offset {})", path,
                                             static_cast<const char*>(z) - text.data()));
  added_.push_back({path, std::make_shared<const std::string>(path), std::move(text)});
  return added_.size() << added_shift;
}

bool ProgramInput::read_added_line(std::string_view& out) {
  const std::string& text = added_[current_ - 1].text;
  line_start_ = tell();
  if (added_pos_ >= text.size()) return false;
  const auto stop = std::min(text.find('\n', added_pos_), text.size());
  out = std::string_view(text).substr(added_pos_, stop - added_pos_);
  added_pos_ = stop + 1;
  diag_.set_line(diag_.line() + 1);
  const auto max_len = static_cast<std::size_t>(tolerances::gcode_max_line_length);
  if (out.size() > max_len)
    diag_.fail(static_cast<int>(max_len) + 1, "line-length", fmt::format("line longer than {} characters", max_len));
  if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
  return true;
}

void ProgramInput::seek(std::size_t offset, long line) {
  if (const std::size_t k = offset >> added_shift; k > 0) {  // into a file added by add_file
    current_ = k;
    added_pos_ = offset - (k << added_shift);
    diag_.set_file(added_[k - 1].name);
    diag_.set_line(line - 1);
    return;
  }
  if (current_ != 0) {  // back into the program
    current_ = 0;
    diag_.set_file(main_name_);
  }
  if (!file_) {
    begin_ = offset;
  } else if (offset >= buffer_offset_ && offset <= buffer_offset_ + end_) {
    begin_ = offset - buffer_offset_;
  } else {
    if (std::fseek(file_, static_cast<long>(offset), SEEK_SET) != 0)
      throw InputError("file", fmt::format("{}: cannot seek back for a loop or subroutine", *diag_.name()));
    buffer_offset_ = offset;
    begin_ = end_ = 0;
    input_eof_ = false;
    fill();
  }
  diag_.set_line(line - 1);
}

bool ProgramInput::read_line(std::string_view& out) {
  if (current_ != 0) return read_added_line(out);
  line_start_ = tell();
  const auto max_len = static_cast<std::size_t>(tolerances::gcode_max_line_length);
  for (;;) {
    const char* d = data();
    const void* nlp = std::memchr(d + begin_, '\n', end_ - begin_);
    if (nlp) {
      const auto stop = static_cast<std::size_t>(static_cast<const char*>(nlp) - d);
      out = std::string_view(d + begin_, stop - begin_);
      begin_ = stop + 1;
      break;
    }
    if (end_ - begin_ > max_len || input_eof_) {
      if (begin_ == end_) return false;
      out = std::string_view(d + begin_, end_ - begin_);
      begin_ = end_;
      break;
    }
    fill();
  }
  diag_.set_line(diag_.line() + 1);
  if (out.size() > max_len)
    diag_.fail(static_cast<int>(max_len) + 1, "line-length", fmt::format("line longer than {} characters", max_len));
  if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
  return true;
}

}  // namespace kontur::gcode::detail
