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


# kontur check: G-code programs (docs/gcode.md)
kontur_cli_case(check_help 0 "CONIC X- Y- Z- I1=- J1=- K1=- I2=- J2=- K2=- I3=- J3=- K3=-" check --help)
kontur_cli_case(help_mentions_check 0 "check.*CONIC" --help)
kontur_cli_case(check_all_block_types 0
                "N200 conic +n/a until conic geometry lands.*5 rapid, 2 line, 1 arc, 1 helix, 2 circle_3d, 1 nurbs, 2 bezier, 1 conic, 1 dwell.*path length 185\\.9678"
                check tests/data/gcode/good/all_block_types.ngc)
kontur_cli_case(check_json 0 "\"type\": \"circle_3d\".*\"path_length_mm\": 185\\.9678" check --json
                tests/data/gcode/good/all_block_types.ngc)
kontur_cli_case(check_3d_chips 0 "4681 line.*path length 5814\\.068986 mm" check --quiet ../shared/data/gcode/3D_Chips.ngc)
kontur_cli_case(check_g6_nurbs_warning 0 "1 nurbs.*warning: G6\\.2 Q1: LinuxCNC's approximation" check
                ../shared/data/gcode/linuxcnc-nurbs/G6_homer-16_n1-1-xy.ngc)
kontur_cli_case(check_knot_count 1
                "kontur: error: tests/data/gcode/bad/knot_count\\.ngc:3:1: G06\\.2: 9 knots given, 10 needed \\(6 control points \\+ rank 4\\)"
                check tests/data/gcode/bad/knot_count.ngc)
kontur_cli_case(check_division_by_zero 1 "division_by_zero\\.ngc:2:7: '/0\\]': division by zero" check
                tests/data/gcode/bad/division_by_zero.ngc)
kontur_cli_case(check_unsupported_g33 1 "g33_simple\\.ngc:4:1: G33: spindle-synchronised motion" check
                ../shared/data/gcode/linuxcnc-tp/spindle/g33_simple.ngc)
kontur_cli_case(check_missing_file 1 "no-such-program\\.ngc: no such file" check no-such-program.ngc)
kontur_cli_case(check_binary_file 1 "binary_file\\.ngc: not a text file" check tests/data/gcode/bad/binary_file.ngc)
kontur_cli_case(check_json_error_exit 1 "kontur: error: .*conic_collinear\\.ngc:3:1: CONIC: points P0, P1 and P4 are collinear" check
                --json tests/data/gcode/bad/conic_collinear.ngc)
