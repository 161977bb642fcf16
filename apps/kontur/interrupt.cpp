#include "interrupt.hpp"

#include <csignal>
#include <cstring>
#include <unistd.h>

namespace kontur::app {
namespace {

volatile std::sig_atomic_t received = 0;  // the signal that came, 0: none

// A job that does not reach a check within this time after the signal (a loop that never hands
// out a setpoint) is ended anyway, and a second signal ends it at once: a stop is never lost.
constexpr unsigned grace_s = 3;

[[noreturn]] void end_now() {
  const char line[] = "kontur: stopped by a signal without cleaning up (the job did not stop in time)\n";
  (void)!write(STDERR_FILENO, line, sizeof line - 1);
  _exit(128 + (received != 0 ? received : SIGTERM));
}

extern "C" void on_alarm(int) { end_now(); }

extern "C" void on_signal(int signal_number) {
  if (received != 0) end_now();
  received = signal_number;
  alarm(grace_s);
}

struct sigaction previous_int, previous_term, previous_alarm;

const char* signal_name(int s) { return s == SIGINT ? "SIGINT" : s == SIGTERM ? "SIGTERM" : "a signal"; }

}  // namespace

Interrupted::Interrupted(int signal_number)
    : std::runtime_error(std::string("stopped by ") + signal_name(signal_number)), signal_(signal_number) {}

InterruptGuard::InterruptGuard() {
  received = 0;
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &previous_int);
  sigaction(SIGTERM, &sa, &previous_term);
  struct sigaction al;
  std::memset(&al, 0, sizeof al);
  al.sa_handler = on_alarm;
  sigemptyset(&al.sa_mask);
  sigaction(SIGALRM, &al, &previous_alarm);
}

InterruptGuard::~InterruptGuard() {
  alarm(0);
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
  sigaction(SIGALRM, &previous_alarm, nullptr);
}

void InterruptGuard::check() {
  if (received != 0) throw Interrupted(received);
}

std::string interrupted_message(const Interrupted& e) {
  std::string files;
  for (const std::string& f : e.not_written) files += (files.empty() ? "" : ", ") + f;
  if (files.empty()) return std::string(e.what()) + " (no file was being written)";
  return std::string(e.what()) + ": " + files + " not written (files from before are as they were)";
}

}  // namespace kontur::app
