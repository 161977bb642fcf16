#pragma once
// Writing an output file so that a reader never sees half of it: the content goes to a new
// temporary file in the same directory (so that the rename stays on one file system), which is
// then renamed over the target. A failure (an exception of the writer, a full disk) removes the
// temporary file and leaves the target as it was. An output that names one of the inputs is
// refused before anything is written.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace kontur {

/// Throws InputError "output-is-input" when `output` names the same file as one of `inputs`
/// (same path after normalisation, or the same file through a link); the message names the file.
void check_output_not_input(const std::filesystem::path& output, const std::vector<std::filesystem::path>& inputs);

/// Writes `path` atomically: `write` fills a stream on a temporary file
/// ".NAME.tmp-PID-N" beside it, which is flushed and renamed to `path`. If `write` throws, or a
/// write, the flush or the rename fails, the temporary file is removed and the exception
/// propagates (InputError "output-write" for I/O failures, naming the file and the reason).
/// `path` is refused when it names one of `inputs` or an existing directory. The file gets the
/// mode 0644.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write,
                           const std::vector<std::filesystem::path>& inputs = {});

}  // namespace kontur
