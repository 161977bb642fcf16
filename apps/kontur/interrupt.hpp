#pragma once
// Clean stops of long jobs: SIGINT (Ctrl-C) and SIGTERM only set a flag; the job checks it where
// it hands out work (each setpoint, each block) and unwinds with Interrupted, so that every output
// still being written is removed (io/atomic_file.hpp) and earlier files stay as they were. main()
// prints one line saying what was not written and exits 128 + the signal (130, 143). A job that
// does not reach a check within 3 s of the signal, or gets a second one, ends at once (_exit).
#include <stdexcept>
#include <string>
#include <vector>

namespace kontur::app {

/// A job stopped by a signal.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal_number);
  /// The signal: SIGINT or SIGTERM.
  [[nodiscard]] int signal_number() const noexcept { return signal_; }
  /// The exit code: 128 + the signal.
  [[nodiscard]] int exit_code() const noexcept { return 128 + signal_; }
  /// The files the job did not write (for the message).
  std::vector<std::string> not_written;

 private:
  int signal_;
};

/// While alive, SIGINT and SIGTERM set a flag instead of ending the process (the handlers before it
/// are restored at its end).
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// Throws Interrupted if a signal came. Cheap enough for every setpoint.
  static void check();
};

/// "kontur: stopped by SIGTERM: out.csv, out.json not written (files from before are as they were)".
[[nodiscard]] std::string interrupted_message(const Interrupted& e);

}  // namespace kontur::app
