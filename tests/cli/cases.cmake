# Command-line cases: kontur_cli_case(NAME EXIT REGEX ARGS...) runs `kontur ARGS...` in the source
# tree and checks the exit code and the output.
function(kontur_cli_case name exit_code regex)
  add_test(NAME cli_${name}
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:kontur_app>;${ARGN}" -DEXPECT_EXIT=${exit_code}
                   "-DEXPECT_REGEX=${regex}" -DWORKDIR=${PROJECT_SOURCE_DIR}
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.cmake)
endfunction()

kontur_cli_case(version 0 "kontur [0-9]+\\.[0-9]+\\.[0-9]+" --version)
kontur_cli_case(help 0 "spline" --help)
kontur_cli_case(no_subcommand 2 "subcommand")
kontur_cli_case(unknown_option 2 "--frobnicate" spline examples/curves/seed_example1.json --frobnicate)
kontur_cli_case(spline_help 0 "Example" spline --help)
kontur_cli_case(spline_seed_example1 0 "-720 +1200 +-420 +-30.*249\\.46310991070" spline examples/curves/seed_example1.json)
kontur_cli_case(spline_seed_example2 0 "252\\.58422861899" spline examples/curves/seed_example2.json)
kontur_cli_case(spline_forward_differences 0 "10 +0\\.5 +1 +-30 +12\\.21 +0\\.06 +-0\\.54" spline
                examples/curves/seed_example1.json --step 0.05)
kontur_cli_case(spline_json 0 "\"gauss_kronrod\"" spline examples/curves/seed_example1.json --json)
kontur_cli_case(spline_seed_g06_2_inconsistent 1 "seed_g06_2_inconsistent\\.json: 9 weights given for 5 control points"
                spline examples/curves/seed_g06_2_inconsistent.json)
kontur_cli_case(spline_missing_file 1 "no-such-curve\\.json: no such file" spline no-such-curve.json)
kontur_cli_case(spline_not_json 1 "CMakeLists\\.txt:1:[0-9]+: not valid JSON" spline CMakeLists.txt)
kontur_cli_case(spline_bad_step 1 "--step -1" spline examples/curves/seed_example1.json --step -1)
kontur_cli_case(spline_feed_fluctuation 0 "taylor1 +2525 .*taylor2 +2525 .*exact +2525 +[0-9.]+e-1[0-9]" spline
                examples/curves/seed_example2.json --feed 6000 --period 0.001)
kontur_cli_case(spline_bad_period 1 "--period 0: must be in \\(0, 1\\]" spline examples/curves/seed_example1.json
                --feed 100 --period 0)
kontur_cli_case(machine_default 0 "max_jerk = 50000" machine)
kontur_cli_case(machine_linuxcnc_ini 0 "max_velocity = 203\\.2" machine ../shared/data/gcode/linuxcnc-tp/configs/XYZ.ini)
kontur_cli_case(machine_missing_file 1 "nowhere\\.toml: no such file" machine nowhere.toml)
