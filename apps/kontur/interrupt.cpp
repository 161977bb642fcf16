#include "interrupt.hpp"

#include <csignal>
#include <cstring>

namespace kontur::app {
namespace {

volatile std::sig_atomic_t received = 0;  // the signal that came, 0: none

extern "C" void on_signal(int signal_number) { received = signal_number; }

struct sigaction previous_int, previous_term;

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
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
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
