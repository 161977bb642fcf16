#include "summary_output.hpp"

#include <iostream>
#include <kontur/io/atomic_file.hpp>

namespace kontur::app {

void write_summary(const std::string& text, const std::string& path, bool quiet,
                   const std::vector<std::filesystem::path>& inputs) {
  if (path.empty()) {
    if (!quiet) std::cerr << text;
  } else if (path == "-") {
    std::cout << text;
  } else {
    write_file_atomically(
        path, [&](std::ostream& out) { out << text; }, inputs);
  }
}

}  // namespace kontur::app
