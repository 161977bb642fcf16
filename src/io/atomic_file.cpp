#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>
#include <system_error>

namespace kontur {
namespace fs = std::filesystem;

namespace {
std::atomic<unsigned> temp_counter{0};

fs::path normalised(const fs::path& p) {
  std::error_code ec;
  const fs::path abs = fs::absolute(p, ec);
  if (ec) return p.lexically_normal();
  const fs::path canon = fs::weakly_canonical(abs, ec);
  return ec ? abs.lexically_normal() : canon;
}
}  // namespace

void check_output_not_input(const fs::path& output, const std::vector<fs::path>& inputs) {
  const fs::path out = normalised(output);
  for (const auto& in : inputs) {
    std::error_code ec;
    const bool same_file = fs::exists(output, ec) && fs::exists(in, ec) && fs::equivalent(output, in, ec) && !ec;
    if (same_file || normalised(in) == out)
      throw InputError("output-is-input",
                       fmt::format("{}: is an input of this command; refusing to overwrite it (choose another output "
                                   "file)",
                                   output.string()));
  }
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write,
                           const std::vector<fs::path>& inputs) {
  check_output_not_input(path, inputs);
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError("output-write", fmt::format("{}: is a directory; give a file name", path.string()));
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec))
    throw InputError("output-write", fmt::format("{}: the directory {} does not exist", path.string(), dir.string()));

  // A device or a pipe (-o /dev/null, a FIFO) is written to as it is: renaming the temporary file
  // over it would replace the device with a file (a run with -o /dev/null did that).
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw InputError("output-write", fmt::format("{}: cannot be opened for writing", path.string()));
    write(out);
    out.flush();
    if (!out) throw InputError("output-write", fmt::format("{}: writing failed", path.string()));
    return;
  }

  // Create the temporary file exclusively, so that no other file is ever truncated.
  fs::path temp;
  for (int attempt = 0;; ++attempt) {
    temp = dir / fmt::format(".{}.tmp-{}-{}", path.filename().string(), static_cast<long>(::getpid()),
                             temp_counter.fetch_add(1));
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ::fchmod(fd, 0644);
      ::close(fd);
      break;
    }
    if (errno != EEXIST || attempt > 100)
      throw InputError("output-write", fmt::format("{}: cannot create a temporary file in {}: {}", path.string(),
                                                   dir.string(), std::strerror(errno)));
  }
  try {
    {
      std::ofstream out(temp, std::ios::binary | std::ios::trunc);
      if (!out) throw InputError("output-write", fmt::format("{}: cannot open {}", path.string(), temp.string()));
      write(out);
      out.flush();
      if (!out) throw InputError("output-write", fmt::format("{}: writing failed", path.string()));
      out.close();
      if (out.fail()) throw InputError("output-write", fmt::format("{}: closing failed", path.string()));
    }
    fs::rename(temp, path, ec);
    if (ec)
      throw InputError("output-write",
                       fmt::format("{}: cannot rename the temporary file to it: {}", path.string(), ec.message()));
  } catch (...) {
    std::error_code ignore;
    fs::remove(temp, ignore);
    throw;
  }
}

}  // namespace kontur
