// The Reader: the program's lines (ProgramInput) through the dialect's front end (lexing and
// control flow) into the dialect-neutral executor, which makes the blocks handed out by next().
#include "cutter_compensation.hpp"
#include "dialect_front_end.hpp"
#include "executor.hpp"

#include <kontur/gcode/reader.hpp>

#include <fmt/format.h>

namespace kontur::gcode {

struct Reader::Impl {
  ReaderOptions opt;
  detail::Diagnostics diag;
  detail::ProgramInput input;
  ParameterTable params;
  detail::Executor executor;
  DialectChoice dialect;
  std::unique_ptr<detail::DialectFrontEnd> front_end;
  detail::Words words;
  detail::CutterCompensation compensation;  // between the executor and next()
  std::vector<Block> out;   // compensated blocks, handed out by next()
  std::size_t head = 0;     // next block of `out` to hand out
  bool finished = false;    // the input ended, or an error was thrown
  bool flushed = false;     // the compensation handed out what it held at the end

  Impl(std::string_view name, ReaderOptions o) : opt(o), diag(name, opt.max_warnings_kept), input(diag), executor(diag, params) {}

  // The dialect given in the options, else `detect()`.
  template <class Detect>
  DialectChoice choose(Detect detect) const {
    if (!opt.dialect) return detect();
    return DialectChoice{*opt.dialect, opt.dialect_reason.empty() ? std::string("given") : opt.dialect_reason};
  }
  // The input is open: the dialect and its front end.
  void start(DialectChoice choice) {
    dialect = std::move(choice);
    opt.dialect = dialect.dialect;
    executor.set_rules(detail::rules_of(dialect.dialect));
    executor.set_arc_radius_tolerances(opt.arc_radius_tolerance_mm.value_or(tolerances::gcode_arc_radius_absolute_mm),
                                       opt.arc_radius_tolerance_inch.value_or(tolerances::gcode_arc_radius_absolute_inch));
    executor.set_tool_table(opt.tool_table.get());
    front_end = detail::make_front_end(dialect.dialect,
                                       detail::DialectServices{dialect.dialect, input, params, diag, opt, executor, &executor});
  }

  // Reads lines until the executor has made blocks or the program has ended.
  void read_more();
};

void Reader::Impl::read_more() {
  std::string_view raw;
  if (!input.read_line(raw)) {
    finished = true;
    front_end->at_end_of_input();
    executor.end_program();
    if (!executor.program_end_seen() && !front_end->program_marks_its_end())
      diag.warn(1, "the program ends without M2, M30 or '%'");
    return;
  }
  switch (front_end->read_line(raw, words)) {
    case detail::LineOutcome::nothing: return;
    case detail::LineOutcome::words:
      executor.execute(words);
      while (!executor.ended() && front_end->pending_words(words)) executor.execute(words);
      return;
    case detail::LineOutcome::program_end: executor.end_program(); return;
  }
}

Reader::Reader(const std::string& path, ReaderOptions options) : impl_(std::make_unique<Impl>(path, options)) {
  impl_->input.open(path);
  impl_->start(impl_->choose([&] { return detect_dialect_of_file(path); }));
}
Reader::Reader(std::string_view name, std::string text, ReaderOptions options)
    : impl_(std::make_unique<Impl>(name, options)) {
  DialectChoice choice = impl_->choose([&] { return detect_dialect(name, text); });
  impl_->input.open_memory(std::move(text));
  impl_->start(std::move(choice));
}
Reader::~Reader() = default;
Reader::Reader(Reader&&) noexcept = default;
Reader& Reader::operator=(Reader&&) noexcept = default;

bool Reader::next(Block& out) {
  Impl& r = *impl_;
  auto& queue = r.executor.blocks();
  while (r.head == r.out.size()) {
    r.out.clear();
    r.head = 0;
    if (r.flushed) return false;
    try {
      if (!queue.empty()) {
        // The executor's blocks through the cutter compensation.
        for (Block& b : queue) r.compensation.push(std::move(b), r.out);
        queue.clear();
      } else if (r.finished || r.executor.ended()) {
        r.compensation.finish(r.out);
        r.flushed = true;
      } else {
        r.read_more();
      }
    } catch (const InputError& e) {
      r.finished = r.flushed = true;  // after an error the reader hands out nothing more
      queue.clear();
      r.out.clear();
      r.head = 0;
      // Every refusal names the dialect it was read in (front ends' own messages already do).
      const std::string message = e.what();
      if (message.find(fmt::format("dialect {}", to_string(r.dialect.dialect))) != std::string::npos) throw;
      throw InputError(e.rule(), fmt::format("{} (dialect {})", message, to_string(r.dialect.dialect)));
    } catch (...) {
      r.finished = r.flushed = true;
      queue.clear();
      r.out.clear();
      r.head = 0;
      throw;
    }
  }
  out = std::move(r.out[r.head++]);
  return true;
}
const std::vector<std::string>& Reader::warnings() const noexcept { return impl_->diag.warnings(); }
std::size_t Reader::warning_count() const noexcept { return impl_->diag.warning_count(); }
long Reader::lines_read() const noexcept { return impl_->diag.line(); }
const DialectChoice& Reader::dialect() const noexcept { return impl_->dialect; }

}  // namespace kontur::gcode
