// Machines and part programs for Python: Machine, check, run (the setpoints as one array),
// RunStream (the same run in chunks, for long jobs) and verify (setpoints from any planner, held in
// arrays or in a file), all through the library's Pipeline, as `kontur run` and `kontur verify`.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <kontur/error.hpp>
#include <kontur/machine.hpp>
#include <kontur/pipeline.hpp>
#include <kontur/report/program_check.hpp>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bindings.hpp"
#include "buffer.hpp"

namespace kontur::python {
namespace {

// How a program is read and run, as the Python keywords give it (kontur/__init__.py).
struct RunArgs {
  bool blend = true;
  bool smooth = true;
  bool check = true;
  bool time_optimal = false;
  std::optional<std::string> dialect;
  bool block_delete = true;
  std::vector<std::string> subroutine_path;
  std::string tool_table;
};

// The dialect named `name` (dialect= of a run, Machine.dialect); InputError for an unknown name.
gcode::Dialect dialect_named(const std::string& name) {
  const auto d = gcode::parse_dialect(name);
  if (!d)
    throw InputError("dialect-name", "dialect = '" + name + "': not a G-code dialect (expected one of " +
                                         gcode::dialect_names() + ")");
  return *d;
}

ProgramReading reading_of(const RunArgs& a) {
  ProgramReading r;
  r.given_reason = "given with dialect=";
  r.block_delete = a.block_delete;
  r.subroutine_path = a.subroutine_path;
  r.tool_table = a.tool_table;
  if (a.dialect) r.dialect = dialect_named(*a.dialect);
  return r;
}

PipelineOptions pipeline_options(const std::string& program, const Machine& machine, const RunArgs& a) {
  PipelineOptions o;
  o.blend = a.blend;
  o.smooth = a.smooth;
  o.check = a.check;
  o.time_optimal = a.time_optimal;
  o.reader = program_reader_options(program, reading_of(a), &machine);
  return o;
}

// One setpoint as a record of 8-byte fields: t [s], the layout's axes [mm] / [deg], v [mm/s], then
// the source line as an int64 (kontur/__init__.py's setpoint_dtype).
void append_record(std::vector<double>& rows, const trajectory::Setpoint& sp) {
  rows.push_back(sp.t_s);
  for (Eigen::Index i = 0; i < sp.position.size(); ++i) rows.push_back(sp.position[i]);
  rows.push_back(sp.v_mm_s);
  const std::int64_t line = sp.source_line;
  double bits;
  std::memcpy(&bits, &line, sizeof bits);
  rows.push_back(bits);
}

// Thrown from a pipeline's callback to stop it: Ctrl-C in Python, or a stream closed early.
struct Stop {};

// Checks for Ctrl-C (KeyboardInterrupt) every so many calls, with the GIL taken for that moment.
class SignalCheck {
 public:
  explicit SignalCheck(long every) : every_(every) {}
  void operator()() {
    if (++calls_ % every_ != 0) return;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      throw Stop{};
    }
  }
  bool interrupted = false;

 private:
  long every_;
  long calls_ = 0;
};

py::dict result_dict(const RunResult& r, const AxisLayout& layout) {
  py::dict d;
  d["axes"] = layout.letters();
  d["summary_json"] = r.summary_json;
  d["passed"] = r.passed;
  d["total_time_s"] = r.total_time_s;
  d["setpoints"] = r.setpoints;
  return d;
}

py::tuple run(const std::string& program, const Machine& machine, const RunArgs& args) {
  validate(machine);
  Pipeline pipeline(machine, pipeline_options(program, machine, args));
  AxisLayout layout;
  {
    py::gil_scoped_release release;  // (prepare() reads the whole program, validating it)
    layout = pipeline.prepare(program);
  }
  std::vector<double> rows;
  RunResult result;
  SignalCheck blocks(256), setpoints(1 << 16);
  {
    py::gil_scoped_release release;
    PipelineEvents events;
    events.setpoint = [&](const trajectory::Setpoint& sp) {
      append_record(rows, sp);
      setpoints();
    };
    events.progress = [&](long) { blocks(); };
    try {
      result = pipeline.run(program, events);
    } catch (const Stop&) {
    }
  }
  if (blocks.interrupted || setpoints.interrupted) throw py::error_already_set();
  const auto record = static_cast<py::ssize_t>(layout.size() + 3);
  const auto n = static_cast<py::ssize_t>(rows.size()) / record;
  return py::make_tuple(Buffer::of(std::move(rows), {n * record * 8}, "B"), result_dict(result, layout));
}

// A run that hands its setpoints out in chunks: the pipeline runs on a thread of its own (it needs
// no Python) and waits while two chunks are ready and not taken, so memory stays flat.
class RunStream {
 public:
  RunStream(const std::string& program, const Machine& machine, const RunArgs& args, long chunk)
      : program_(program), pipeline_((validate(machine), machine), pipeline_options(program, machine, args)), chunk_(chunk) {
    if (chunk_ < 1) throw InputError("chunk-positive", "chunk = " + std::to_string(chunk) + ": expected at least 1 setpoint");
    py::gil_scoped_release release;  // (prepare() reads the whole program, validating it)
    layout_ = pipeline_.prepare(program);
  }
  RunStream(const RunStream&) = delete;
  RunStream& operator=(const RunStream&) = delete;
  ~RunStream() { close(); }

  [[nodiscard]] const AxisLayout& layout() const noexcept { return layout_; }

  // The next chunk (bytes of records), or None at the end; rethrows the run's error.
  py::object next() {
    if (!thread_.joinable() && !finished_) thread_ = std::thread([this] { work(); });
    std::vector<double> chunk;
    for (;;) {
      bool ready = false, done = false;
      {
        py::gil_scoped_release release;
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait_for(lock, std::chrono::milliseconds(100), [&] { return !queue_.empty() || finished_; });
        if (!queue_.empty()) {
          chunk = std::move(queue_.front());
          queue_.pop_front();
          ready = true;
        } else {
          done = finished_;
        }
      }
      if (ready) {
        cv_.notify_all();
        break;
      }
      if (done) {
        if (error_) {
          std::exception_ptr e = error_;
          error_ = nullptr;
          std::rethrow_exception(e);
        }
        return py::none();
      }
      if (PyErr_CheckSignals() != 0) {
        close();
        throw py::error_already_set();
      }
    }
    const auto bytes = static_cast<py::ssize_t>(chunk.size() * sizeof(double));
    return py::cast(Buffer::of(std::move(chunk), {bytes}, "B"));
  }

  // Stops the run (if it goes on) and waits for its thread.
  void close() {
    cancelled_ = true;
    cv_.notify_all();
    if (thread_.joinable()) {
      py::gil_scoped_release release;
      thread_.join();
    }
  }

  [[nodiscard]] py::object result() const {
    if (!finished_ || cancelled_) return py::none();
    return result_dict(result_, layout_);
  }

 private:
  void work() {
    const auto record = static_cast<std::size_t>(layout_.size() + 3);
    const std::size_t full = record * static_cast<std::size_t>(chunk_);
    try {
      std::vector<double> chunk;
      chunk.reserve(full);
      PipelineEvents events;
      events.setpoint = [&](const trajectory::Setpoint& sp) {
        if (cancelled_) throw Stop{};
        append_record(chunk, sp);
        if (chunk.size() >= full) {
          push(std::move(chunk));
          chunk = {};
          chunk.reserve(full);
        }
      };
      events.progress = [&](long) {
        if (cancelled_) throw Stop{};
      };
      RunResult r = pipeline_.run(program_, events);
      if (!chunk.empty()) push(std::move(chunk));
      result_ = std::move(r);
    } catch (const Stop&) {
    } catch (...) {
      error_ = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_ = true;
    }
    cv_.notify_all();
  }
  void push(std::vector<double>&& chunk) {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [&] { return queue_.size() < 2 || cancelled_; });
    if (cancelled_) throw Stop{};
    queue_.push_back(std::move(chunk));
    lock.unlock();
    cv_.notify_all();
  }

  std::string program_;
  Pipeline pipeline_;
  AxisLayout layout_ = AxisLayout::xyz();
  long chunk_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::vector<double>> queue_;
  std::atomic<bool> cancelled_{false};
  std::atomic<bool> finished_{false};
  std::exception_ptr error_;
  RunResult result_;
};

py::dict verify(const std::string& program, const Machine& machine, const RunArgs& args, const std::string& letters,
                const py::buffer& t_values, const std::vector<py::buffer>& axis_values, const py::buffer& v_values,
                const py::buffer& line_values, const std::string& source_name) {
  validate(machine);
  const AxisLayout layout = AxisLayout::from_letters(letters);
  if (static_cast<int>(axis_values.size()) != layout.size())
    throw py::value_error("setpoints: " + std::to_string(axis_values.size()) + " axis columns for the axes " + letters);
  const DoubleView t(t_values, 1, "setpoints['t']"), v(v_values, 1, "setpoints['v']"),
      line(line_values, 1, "setpoints['block']");
  std::vector<DoubleView> axes;
  for (std::size_t i = 0; i < axis_values.size(); ++i)
    axes.emplace_back(axis_values[i], 1, "setpoints axis column");
  const py::ssize_t n = t.rows();
  for (const DoubleView& c : axes)
    if (c.rows() != n) throw py::value_error("setpoints: columns of different lengths");
  if (v.rows() != n || line.rows() != n) throw py::value_error("setpoints: columns of different lengths");
  RunArgs a = args;
  a.check = true;
  Pipeline pipeline(machine, pipeline_options(program, machine, a));
  RunResult result;
  {
    py::gil_scoped_release release;
    result = pipeline.verify(program, source_name, [&](const HeaderVisitor& header, const SetpointVisitor& visit) {
      SetpointHeader h;
      h.layout = layout;
      header(h);
      trajectory::Setpoint sp;
      sp.position = AxisVector::Zero(layout.size());
      for (py::ssize_t i = 0; i < n; ++i) {
        sp.t_s = t(i);
        for (int k = 0; k < layout.size(); ++k) sp.position[k] = axes[static_cast<std::size_t>(k)](i);
        sp.v_mm_s = v(i);
        sp.source_line = static_cast<long>(line(i));
        visit(sp);
      }
    });
  }
  return result_dict(result, layout);
}

py::dict verify_file(const std::string& program, const Machine& machine, const RunArgs& args, const std::string& path) {
  validate(machine);
  RunArgs a = args;
  a.check = true;
  Pipeline pipeline(machine, pipeline_options(program, machine, a));
  RunResult result;
  {
    py::gil_scoped_release release;
    result = pipeline.verify(program, path);
  }
  return result_dict(result, pipeline.layout());
}

py::list axes_of(const Machine& m) {
  py::list out;
  for (const AxisLimits& a : m.axes) {
    py::dict d;
    d["name"] = std::string(1, a.name);
    d["rotary"] = a.rotary;
    d["max_velocity"] = a.max_velocity;
    d["max_acceleration"] = a.max_acceleration;
    d["max_jerk"] = a.max_jerk;
    d["min_position"] = a.min_position;
    d["max_position"] = a.max_position;
    out.append(d);
  }
  return out;
}

void set_axis(Machine& m, const std::string& name, std::optional<double> max_velocity,
              std::optional<double> max_acceleration, std::optional<double> max_jerk,
              std::optional<double> min_position, std::optional<double> max_position) {
  for (AxisLimits& a : m.axes)
    if (name.size() == 1 && a.name == name[0]) {
      if (max_velocity) a.max_velocity = *max_velocity;
      if (max_acceleration) a.max_acceleration = *max_acceleration;
      if (max_jerk) a.max_jerk = *max_jerk;
      if (min_position) a.min_position = *min_position;
      if (max_position) a.max_position = *max_position;
      validate(m);
      return;
    }
  std::string names;
  for (const AxisLimits& a : m.axes) names += a.name;
  throw InputError("axis-name", "axis '" + name + "': the machine has no such axis (its axes: " + names + ")");
}

}  // namespace

void bind_runs(py::module_& m) {
  py::class_<RunArgs>(m, "RunArgs", "How a program is read and run (kontur.run's keywords).")
      .def(py::init<>())
      .def_readwrite("blend", &RunArgs::blend)
      .def_readwrite("smooth", &RunArgs::smooth)
      .def_readwrite("check", &RunArgs::check)
      .def_readwrite("time_optimal", &RunArgs::time_optimal)
      .def_readwrite("dialect", &RunArgs::dialect)
      .def_readwrite("block_delete", &RunArgs::block_delete)
      .def_readwrite("subroutine_path", &RunArgs::subroutine_path)
      .def_readwrite("tool_table", &RunArgs::tool_table);

  py::class_<Machine>(m, "Machine", "The library's kontur::Machine; see kontur.Machine.")
      .def(py::init([](const Machine& other) { return Machine(other); }), py::arg("other"))
      .def_static("load", [](const std::string& path) { return read_machine(path); }, py::arg("path"))
      .def_static("default", [] {
        Machine d = default_machine();
        validate(d);
        return d;
      })
      .def_readwrite("name", &Machine::name)
      .def_readonly("source", &Machine::source)
      .def_readwrite("max_feed_mm_s", &Machine::max_feed_mm_s)
      .def_readwrite("rapid_feed_mm_s", &Machine::rapid_feed_mm_s)
      .def_readwrite("chord_tolerance_mm", &Machine::chord_tolerance_mm)
      .def_readwrite("path_tolerance_mm", &Machine::path_tolerance_mm)
      .def_readwrite("servo_period_s", &Machine::servo_period_s)
      .def_property(
          "dialect",
          [](const Machine& s) -> std::optional<std::string> {
            if (!s.dialect) return std::nullopt;
            return std::string(gcode::to_string(*s.dialect));
          },
          [](Machine& s, const std::optional<std::string>& name) {
            if (!name) {
              s.dialect.reset();
              return;
            }
            s.dialect = dialect_named(*name);
          })
      .def_property_readonly("axes", &axes_of)
      .def("set_axis", &set_axis, py::arg("name"), py::arg("max_velocity") = py::none(),
           py::arg("max_acceleration") = py::none(), py::arg("max_jerk") = py::none(),
           py::arg("min_position") = py::none(), py::arg("max_position") = py::none())
      .def("validate", [](const Machine& s) { validate(s); })
      .def("to_toml", [](const Machine& s) { return to_toml(s); });

  m.def(
      "check",
      [](const std::string& program, const Machine* machine, const RunArgs& args, bool blocks) {
        const gcode::ReaderOptions ro = program_reader_options(program, reading_of(args), machine);
        py::gil_scoped_release release;
        return report::program_check_json(program, ro, blocks);
      },
      py::arg("program"), py::arg("machine").none(true), py::arg("args"), py::arg("blocks"));
  m.def("run", &run, py::arg("program"), py::arg("machine"), py::arg("args"));
  m.def("verify_file", &verify_file, py::arg("program"), py::arg("machine"), py::arg("args"), py::arg("path"));
  m.def("verify", &verify, py::arg("program"), py::arg("machine"), py::arg("args"), py::arg("axes"), py::arg("t"),
        py::arg("positions"), py::arg("v"), py::arg("block"), py::arg("source_name"));

  py::class_<RunStream>(m, "RunStream", "A run handing out its setpoints in chunks; see kontur.run_iter.")
      .def(py::init<const std::string&, const Machine&, const RunArgs&, long>(), py::arg("program"), py::arg("machine"),
           py::arg("args"), py::arg("chunk"))
      .def_property_readonly("axes", [](const RunStream& s) { return s.layout().letters(); })
      .def("next", &RunStream::next)
      .def("close", &RunStream::close)
      .def("result", &RunStream::result);
}

}  // namespace kontur::python
