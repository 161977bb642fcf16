// The `kontur` command: one subcommand per job, the library does the work.
#include "commands.hpp"
#include "interrupt.hpp"
#include "report_output.hpp"

#include <kontur/error.hpp>
#include <kontur/version.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  using namespace kontur::app;
  CLI::App app{"kontur: motion interpolation for CNC machines and robots.\n"
               "Exit codes: 0 success, 1 invalid input (file, curve, value), 2 wrong command line, "
               "3 internal error, 4 (run) setpoints outside the limits, 130 / 143 stopped by SIGINT / SIGTERM.",
               "kontur"};
  app.set_version_flag("--version", std::string("kontur ") + kontur::version_string);
  app.require_subcommand(1);
  app.footer("Example:\n  kontur spline examples/curves/seed_example1.json --step 0.05\n"
             "  kontur arc 110,100,50 100,110,50 90,100,50 --omega 0.5 --steps 4\n"
             "  kontur check program.ngc\n"
             "  kontur run examples/programs/square_arc.ngc -o square_arc.csv --report square_arc.html\n"
             "G-code: RS274 core with LinuxCNC, Fanuc and Sinumerik extensions; Kontur's own conic block is\n"
             "  CONIC X- Y- Z- I1=- J1=- K1=- I2=- J2=- K2=- I3=- J3=- K3=- (see `kontur check --help`).\n"
             "  kontur spline examples/curves/seed_example1.json --report spline.html   (open it in a browser)\n"
             "Run `kontur SUBCOMMAND --help` for the options of each subcommand.");
  int exit_code = exit_ok;
  set_invocation(argc, argv);
  register_spline_command(app, exit_code);
  register_machine_command(app, exit_code);
  register_run_command(app, exit_code);
  register_verify_command(app, exit_code);
  register_replay_command(app, exit_code);
  register_arc_command(app, exit_code);
  register_conic_command(app, exit_code);
  register_check_command(app, exit_code);
  register_compress_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return exit_usage;
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "kontur: %s\n", interrupted_message(e).c_str());
    return e.exit_code();
  } catch (const kontur::InputError& e) {
    std::fprintf(stderr, "kontur: error: %s\n", e.what());
    return exit_invalid_input;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kontur: internal error: %s\n", e.what());
    return exit_internal;
  }
  return exit_code;
}
