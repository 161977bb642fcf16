#pragma once
// plotly.js, embedded at build time (cmake/embed_plotly.cmake writes the definitions from
// node_modules/plotly.js-dist-min/plotly.min.js). With KONTUR_BUILD_REPORT=OFF the chunk count
// is 0 and the report writer says so.
#include <cstddef>
#include <string_view>

namespace kontur::report::detail {

extern const char* const plotly_version;        ///< version of plotly.js-dist-min, or "" when not embedded
extern const std::size_t plotly_size;           ///< total bytes of the script
extern const std::string_view plotly_chunks[];  ///< the script, in pieces to concatenate
extern const std::size_t plotly_chunk_count;    ///< number of pieces (0: not embedded)

}  // namespace kontur::report::detail
