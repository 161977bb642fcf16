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
                "N200 conic +24\\.834694 .*5 rapid, 2 line, 1 arc, 1 helix, 2 circle_3d, 1 nurbs, 2 bezier, 1 conic, 1 dwell.*path length 210\\.8025"
                check tests/data/gcode/good/all_block_types.ngc)
kontur_cli_case(check_json 0 "\"type\": \"circle_3d\".*\"path_length_mm\": 210\\.8025" check --json
                tests/data/gcode/good/all_block_types.ngc)
kontur_cli_case(check_extra_axes 0 "line +25\\.400000 2540 mm/min \\[A 0\\.000000 -> 100\\.000000 deg\\]" check
                ../shared/data/gcode/linuxcnc-tp/diagnostic/abc_tangent.ngc)
kontur_cli_case(check_extra_axes_json 0 "\"extra_start\": {[^}]*\"A\": 0\\.0[^}]*},[^\"]*\"extra_end\": {[^}]*\"A\": 100\\.0" check
                --json ../shared/data/gcode/linuxcnc-tp/diagnostic/abc_tangent.ngc)
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
kontur_cli_case(check_json_error_exit 1 "kontur: error: .*conic_collinear\\.ngc:3:1: CONIC: r1, r2 and r5 are collinear" check
                --json tests/data/gcode/bad/conic_collinear.ngc)

# kontur arc / kontur conic (methods.md sections 4 and 5)
kontur_cli_case(arc_help 0 "Example" arc --help)
kontur_cli_case(conic_help 0 "Example" conic --help)
kontur_cli_case(arc_reference_1 0 "centre r0 = \\(100, 100, 50\\) mm, radius R = 10 mm.*t = 6\\.283185307 s.*V = l / t = 5 mm/s.*107\\.071068 +107\\.071068 +50\\.000000.*92\\.928932 +107\\.071068"
                arc 110,100,50 100,110,50 90,100,50 --omega 0.5 --steps 4)
kontur_cli_case(arc_reference_2 0 "radius R = 97\\.60388424 mm.*theta13 = 2\\.66696426 rad \\(152\\.8057965 deg\\).*omega = 0\\.2666964.*138\\.517634 +233\\.188777 +292\\.150597"
                arc 100,200,300 200,250,310 260,180,400 --time 10 --steps 5)
kontur_cli_case(arc_full_circle 0 "motion type 2.*arc angle theta = 6\\.28318531 rad \\(360 deg\\)"
                arc 110,100,50 100,110,50 90,100,50 --full --omega 1 --steps 8)
kontur_cli_case(arc_negative_coordinates 0 "radius R = 1 mm" arc -1,0,0 0,1,0 1,0,0 --time 2 --steps 2)
kontur_cli_case(arc_csv 0 "^i,t_s,angle_rad,x_rel_mm,y_rel_mm,z_rel_mm,x_mm,y_mm,z_mm\n0,0,0,10,0,0,110,100,50\n"
                arc 110,100,50 100,110,50 90,100,50 --omega 0.5 --steps 4 --csv)
kontur_cli_case(arc_json 0 "\"radius_mm\": 10" arc 110,100,50 100,110,50 90,100,50 --omega 0.5 --steps 4 --json)
kontur_cli_case(arc_feed_csv 0 "^k,t_s,s_mm,u,x_mm,y_mm,z_mm\n.*\n7,3\\.5,31\\.4159265358979[0-9]*,1,90,100,50\n$"
                arc 110,100,50 100,110,50 90,100,50 --feed 600 --period 0.5 --csv)
kontur_cli_case(arc_collinear 1 "^kontur: error: r1 \\(1, 1, 1\\), r2 \\(2, 2, 2\\) and r3 \\(3, 3, 3\\) are collinear"
                arc 1,1,1 2,2,2 3,3,3 --omega 1 --steps 3)
kontur_cli_case(arc_coincident 1 "^kontur: error: r1 \\(1, 1, 1\\) and r3 \\(1, 1, 1\\) coincide"
                arc 1,1,1 2,2,2 1,1,1 --omega 1 --steps 3)
kontur_cli_case(arc_omega_negative 1 "^kontur: error: --omega -1: the angular speed must be finite and > 0"
                arc 1,1,1 2,2,2 3,3,4 --omega -1 --steps 3)
kontur_cli_case(arc_time_zero 1 "^kontur: error: --time 0: the time must be finite and > 0"
                arc 1,1,1 2,2,2 3,3,4 --time 0 --steps 3)
kontur_cli_case(arc_steps_zero 1 "^kontur: error: --steps 0: N must be >= 1" arc 1,1,1 2,2,2 3,3,4 --omega 1 --steps 0)
kontur_cli_case(arc_not_finite 1 "^kontur: error: r2\\.z = nan: every coordinate must be a finite number"
                arc 1,1,1 2,2,nan 3,3,4 --omega 1 --steps 2)
kontur_cli_case(arc_bad_point 1 "^kontur: error: P2 = '2,2': a point is x,y,z" arc 1,1,1 2,2 3,3,4 --omega 1 --steps 2)
kontur_cli_case(arc_outside_limits 1 "^kontur: error: r2: y = 110 mm is above the machine limit 105 mm\n$"
                arc 110,100,50 100,110,50 90,100,50 --omega 1 --steps 2 --limits 1,1,1,5000,105,5000)
kontur_cli_case(arc_bulges_outside_limits 1 "^kontur: error: step 1: y = 110(\\.0+[0-9]*)? mm is above the machine limit 109 mm"
                arc 110,100,50 107.0710678118655,107.0710678118655,50 90,100,50 --omega 1 --steps 2 --limits 0,0,0,200,109,200)
kontur_cli_case(arc_no_mode 1 "give --omega W or --time T" arc 1,1,1 2,2,2 3,3,4)
kontur_cli_case(arc_both_modes 1 "give one of them" arc 1,1,1 2,2,2 3,3,4 --omega 1 --time 2 --steps 2)
kontur_cli_case(conic_reference_ellipse 0 "type: ellipse.*a = 5 mm, b = 3 mm, focal distance c = 4 mm.*theta15 = 2\\.92027821 rad \\(167\\.3196165 deg\\).*t = 5\\.840556422 s.*104\\.840316 +200\\.451271 +300\\.601695.*102\\.048748 +201\\.641957 +302\\.189275"
                conic 105,200,300 104,201.08,301.44 103,201.44,301.92 100,201.8,302.4 96,201.08,301.44 --omega 0.5 --steps 4)
kontur_cli_case(conic_reference_parabola 0 "type: parabola.*focal parameter p = 2 mm.*theta15 = 4\\.71238898 rad \\(270 deg\\).*t = 9\\.424777961 s"
                conic 96,202.4,303.2 98,200.6,300.8 100,200,300 102,200.6,300.8 106,205.4,307.2 --omega 0.5 --steps 4)
kontur_cli_case(conic_reference_hyperbola 0 "type: hyperbola.*e = 1\\.25.*p = 2\\.25 mm.*a = 4 mm, b = 3 mm, focal distance c = 5 mm.*243\\.7815836 deg.*t = 8\\.509582579 s"
                conic 108.5,196.625,295.5 105,198.65,298.2 104,200,300 105,201.35,301.8 108.5,203.375,304.5 --omega 0.5 --steps 4)
kontur_cli_case(conic_json 0 "\"type\": \"ellipse\"" conic 105,200,300 104,201.08,301.44 103,201.44,301.92
                100,201.8,302.4 96,201.08,301.44 --time 2 --steps 4 --json)
kontur_cli_case(conic_feed 0 "constant feed F = 600 mm/min.*0\\.01 mm per period"
                conic 105,200,300 104,201.08,301.44 103,201.44,301.92 100,201.8,302.4 96,201.08,301.44 --feed 600 --period 0.001)
kontur_cli_case(conic_not_coplanar 1 "^kontur: error: r5 \\(96, 201\\.08, 301\\.5\\) is 0\\.0[0-9]+ mm from the plane of r1, r2, r3 \\(tolerance 9\\.1[0-9]e-09 mm\\)"
                conic 105,200,300 104,201.08,301.44 103,201.44,301.92 100,201.8,302.4 96,201.08,301.5 --omega 1 --steps 4)
kontur_cli_case(conic_plane_tolerance 0 "type: ellipse" conic 105,200,300 104,201.08,301.44 103,201.44,301.92
                100,201.8,302.4 96,201.08,301.4401 --omega 1 --steps 4 --plane-tolerance 0.001)
kontur_cli_case(conic_collinear 1 "^kontur: error: r1, r2 and r3 are collinear.*two intersecting lines"
                conic 0,0,0 2,0,0 5,0,0 8,2,0 6,4,0 --omega 1 --steps 4)
kontur_cli_case(conic_parallel_lines 1 "two parallel lines" conic 0,0,0 2,0,0 5,0,0 8,2,0 1,2,0 --omega 1 --steps 4)
kontur_cli_case(conic_not_in_order 1 "^kontur: error: the points are not in order along one arc of the ellipse"
                conic 105,200,300 104,201.08,301.44 100,201.8,302.4 103,201.44,301.92 96,201.08,301.44 --omega 1 --steps 4)
kontur_cli_case(conic_two_branches 1 "^kontur: error: r4 \\(95, 201\\.35, 301\\.8\\) lies on the other branch"
                conic 108.5,196.625,295.5 105,198.65,298.2 104,200,300 95,201.35,301.8 91.5,203.375,304.5 --omega 1 --steps 4)
kontur_cli_case(conic_coincident 1 "coincide" conic 1,0,0 0,1,0 1,0,0 0,-1,0 2,2,0 --omega 1 --steps 4)
kontur_cli_case(conic_outside_limits 1 "^kontur: error: r1: x = 105 mm is above the machine limit 104 mm"
                conic 105,200,300 104,201.08,301.44 103,201.44,301.92 100,201.8,302.4 96,201.08,301.44 --omega 1 --steps 4
                --limits 0,0,0,104,400,400)

# --report FILE (docs/report.md): written atomically, never over an input, nothing on failure.
if(KONTUR_BUILD_REPORT)
  set(report_dir ${CMAKE_CURRENT_BINARY_DIR}/cli-reports)
  file(MAKE_DIRECTORY ${report_dir})
  kontur_cli_case(spline_report 0 "249\\.46310991070" spline examples/curves/seed_example1.json --report
                  ${report_dir}/spline.html)
  kontur_cli_case(spline_report_refuses_input 1
                  "^kontur: error: examples/curves/seed_example1\\.json: is an input of this command; refusing to overwrite it"
                  spline examples/curves/seed_example1.json --report examples/curves/seed_example1.json)
  kontur_cli_case(arc_report_stdout 0 "^<!DOCTYPE html>.*plotly\\.js v.*kontur-data.*</html>\n$"
                  arc 110,100,50 100,110,50 90,100,50 --omega 0.5 --steps 4 --report -)
  kontur_cli_case(conic_report_missing_dir 1 "^kontur: error: .*no/such/dir/c\\.html: the directory .* does not exist"
                  conic 105,200,300 104,201.08,301.44 103,201.44,301.92 100,201.8,302.4 96,201.08,301.44 --omega 0.5
                  --steps 4 --report ${report_dir}/no/such/dir/c.html)
  kontur_cli_case(arc_report_help 0 "--report FILE" arc --help)
  # Invalid input: exit 1 and no report file at all.
  add_test(NAME cli_arc_report_invalid_input_writes_nothing
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:kontur_app>;arc;1,1,1;2,2,2;3,3,3;--omega;1;--steps;3;--report;${report_dir}/collinear.html"
                   -DEXPECT_EXIT=1 "-DEXPECT_REGEX=collinear" -DNO_FILE=${report_dir}/collinear.html
                   -DWORKDIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.cmake)
  # kontur run --report: one self-contained file with the run's plots and the block table.
  add_test(NAME cli_run_report_written
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:kontur_app>;run;examples/programs/square_arc.ngc;-o;${report_dir}/run.csv;--summary;${report_dir}/run.json;--report;${report_dir}/run.html"
                   -DEXPECT_EXIT=0 -DEXPECT_FILE=${report_dir}/run.html
                   "-DEXPECT_FILE_REGEX=^<!DOCTYPE html>.*</html>\n$" "-DEXPECT_FILE_REGEX2=Axis jerk over time"
                   "-DEXPECT_FILE_REGEX3=Blocks \\(click a row"
                   -DEMPTY_STDERR=ON -DWORKDIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.cmake)
  add_test(NAME cli_run_report_bad_program_writes_nothing
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:kontur_app>;run;tests/data/gcode/bad/knot_count.ngc;-o;${report_dir}/bad.csv;--report;${report_dir}/bad.html"
                   -DEXPECT_EXIT=1 "-DEXPECT_REGEX=knot_count\\.ngc:3:1: G06\\.2: 9 knots given" -DNO_FILE=${report_dir}/bad.html
                   -DWORKDIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.cmake)
  kontur_cli_case(run_report_refuses_to_overwrite_its_program 1
                  "square_arc\\.ngc: is an input of this command; refusing to overwrite it" run
                  examples/programs/square_arc.ngc -o ${report_dir}/run2.csv --report examples/programs/square_arc.ngc)
  kontur_cli_case(run_report_refuses_the_setpoint_file 1 "run3\\.csv: is an input" run
                  examples/programs/square_arc.ngc -o ${report_dir}/run3.csv --report ${report_dir}/run3.csv)
  kontur_cli_case(run_report_stdout_not_with_setpoints_on_stdout 2 "--report - needs -o FILE or no -o" run
                  examples/programs/square_arc.ngc -o - --report -)
endif()

# kontur run (issue 5, in progress): the bundled example passes the independent check.
kontur_cli_case(run_example 0 "t,x,y,z,v,block.*PASS +every limit held" run examples/programs/square_arc.ngc -o -)
# Without -o (issue 19): no setpoints, the short summary on stdout and how to write them; --json the JSON.
kontur_cli_case(run_without_output_prints_the_short_summary 0
                "time +5\\.174 s, 5175 setpoints.*PASS +every limit held.*setpoints not written: -o FILE" run
                examples/programs/square_arc.ngc)
kontur_cli_case(run_json_prints_the_summary 0 "\"total_time_s\": 5\\.174,.*\"passed\": true" run
                examples/programs/square_arc.ngc --json --quiet)
kontur_cli_case(run_json_not_with_setpoints_on_stdout 2 "stdout is taken" run examples/programs/square_arc.ngc
                -o - --json)
kontur_cli_case(run_segments_need_an_output 2 "--format segments needs -o FILE" run examples/programs/square_arc.ngc
                --format segments)
# Four axes (issue 14): the rotary example in inverse time writes an A column and passes; a program
# that moves A on a machine without it is refused, naming the axis, the line and the machine.
kontur_cli_case(run_rotary_g93 0 "\"max_extra_axis_error\": [0-9.e-]+,[^}]*\"passed\": true" run
                examples/programs/rotary_g93.ngc --machine examples/machines/router_4axis.toml
                -o /tmp/kontur_cli_rotary.csv --summary -)
kontur_cli_case(run_rotary_g93_columns 0 "^t,x,y,z,a,v,block\n0\\.000000000,0,0,0,0,0\\.000000,4" run
                examples/programs/rotary_g93.ngc --machine examples/machines/router_4axis.toml -o - --quiet)
kontur_cli_case(run_axis_the_machine_lacks 1
                "rotary_g93\\.ngc:8: the block moves A \\(to 30\\), but the machine .* has no A axis \\(its axes: X Y Z\\)" run
                examples/programs/rotary_g93.ngc -o /tmp/kontur_cli_rotary_refused.csv)
# ... and a linear axis the machine lacks (LinuxCNC's XY.ini: COORDINATES X Y), on the program's line.
kontur_cli_case(run_linear_axis_refused 1
                "tangent_helix\\.ngc:4: the block moves Z \\(to -6\\.8[0-9]*\\), but the machine .* has no Z axis \\(its axes: X Y\\)" run
                ../shared/data/gcode/linuxcnc-tp/quick-tests/tangent_helix.ngc --machine ../shared/data/gcode/linuxcnc-tp/configs/XY.ini -o /tmp/kontur_cli_linear_axis_refused.csv)
# --time-optimal: the reference time and the ratio (>= 1: the reference is a lower bound).
kontur_cli_case(run_time_optimal 0 "\"time_optimal_s\": [0-9.]+,[^}]*\"time_ratio\": 1\\.[0-9]+" run examples/programs/square_arc.ngc --time-optimal -o /tmp/kontur_cli_run_time_optimal.csv --json)
# ... and each block the reference's time on its move, after its chord error.
kontur_cli_case(run_time_optimal_per_block 0 "\"max_chord_error_mm\": [-0-9.e]+,[^\"]*\"time_optimal_s\": 0\\.[0-9]+" run examples/programs/square_arc.ngc --time-optimal --json)
kontur_cli_case(run_bad_program 1 "knot_count\\.ngc:[0-9]+:[0-9]+: G0?6\\.2: [0-9]+ knots given" run tests/data/gcode/bad/knot_count.ngc -o /tmp/kontur_cli_run_bad.csv)
kontur_cli_case(run_refuses_to_overwrite_its_program 1 "square_arc\\.ngc" run examples/programs/square_arc.ngc -o examples/programs/square_arc.ngc)
kontur_cli_case(run_help 0 "Example:.*--report" run --help)
kontur_cli_case(machine_help 0 "Example" machine --help)
kontur_cli_case(run_summary_has_blocks 0 "\"blocks\": \\[.*\"line\": 3,.*\"type\": \"rapid\".*\"max_jerk_ratio\"" run
                examples/programs/square_arc.ngc -o /tmp/kontur_cli_run_blocks.csv --summary -)
# --quiet: nothing on stderr on success (no summary, no progress bar); the setpoints still go to stdout.
add_test(NAME cli_run_quiet_prints_nothing_to_stderr
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:kontur_app>;run;examples/programs/square_arc.ngc;-o;-;--quiet"
                 -DEXPECT_EXIT=0 "-DEXPECT_REGEX=^t,x,y,z,v,block\n" -DEMPTY_STDERR=ON
                 -DWORKDIR=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.cmake)

# kontur verify: a setpoint file (written once by kontur run, kept as data: its check does not
# depend on the planner), the same with one setpoint moved by 0.01 mm, and broken files.
kontur_cli_case(verify_help 0 "Example" verify --help)
kontur_cli_case(verify_setpoints_within_limits 0 "\"passed\": true" verify tests/data/setpoints/short_line.ngc
                tests/data/setpoints/short_line.csv --summary -)
kontur_cli_case(verify_prints_the_short_summary 0 "checked +tests/data/setpoints/short_line\\.csv" verify
                tests/data/setpoints/short_line.ngc tests/data/setpoints/short_line.csv)
kontur_cli_case(verify_bumped_setpoint_fails 4 "jerk of axis Y at [0-9.]+ times its limit.*0\\.00894 mm off the path" verify
                tests/data/setpoints/short_line.ngc tests/data/setpoints/short_line_bumped.csv)
kontur_cli_case(verify_bad_header 1 "bad_header\\.csv:1: the header is \"time,x,y,z\"" verify
                tests/data/setpoints/short_line.ngc tests/data/setpoints/bad_header.csv)
kontur_cli_case(verify_bad_row 1 "bad_row\\.csv:3: column 3 of \"0\\.001000000,0,zero,0,0\\.000000,3\" is not a number" verify
                tests/data/setpoints/short_line.ngc tests/data/setpoints/bad_row.csv)
kontur_cli_case(verify_missing_setpoints 1 "no-such\\.csv: cannot open the setpoint file" verify
                tests/data/setpoints/short_line.ngc tests/data/setpoints/no-such.csv)
# Setpoints and summary cannot both go to stdout: refused before any work.
kontur_cli_case(run_summary_stdout_not_with_setpoints_on_stdout 2 "stdout is taken" run
                examples/programs/square_arc.ngc -o - --summary -)

# the tool table (docs/gcode.md, "Tool table and compensation")
kontur_cli_case(check_tool_table 0 "rapid +25\\.000000 mm" check tests/data/gcode/good/tool_length.ngc
                --tool-table tests/data/tools/mill.tbl)
kontur_cli_case(check_compensation_without_tool_table 1
                "cutter_compensation\\.ngc:4:5: G41 D1: the radius of tool 1 is unknown: no tool table given"
                check tests/data/gcode/good/cutter_compensation.ngc)
kontur_cli_case(check_compensation 0 "blocks +2 rapid, 3 line" check tests/data/gcode/good/cutter_compensation.ngc
                --tool-table tests/data/tools/mill.tbl)
kontur_cli_case(check_tool_table_twice 1 "twice\\.tbl:2: tool-twice: T1: the tool is in the table twice" check
                tests/data/gcode/good/tool_length.ngc --tool-table tests/data/tools/twice.tbl)
kontur_cli_case(check_tool_table_missing 1 "no-such\\.tbl: tool-table: cannot open the tool table" check
                tests/data/gcode/good/tool_length.ngc --tool-table no-such.tbl)
kontur_cli_case(run_cutter_compensation 0 "\"passed\": true" run tests/data/gcode/good/cutter_compensation.ngc
                --tool-table tests/data/tools/mill.tbl -o /tmp/kontur_cli_comp.csv --summary -)

# The segment stream (docs/segments.md): run -> replay -> verify, a stream verified directly, and
# streams refused.
add_test(NAME cli_segments_round_trip
         COMMAND ${CMAKE_COMMAND} -DKONTUR=$<TARGET_FILE:kontur_app> -DWORKDIR=${PROJECT_SOURCE_DIR}
                 -DOUT=${CMAKE_CURRENT_BINARY_DIR}/segments_round_trip -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/segments_round_trip.cmake)
kontur_cli_case(replay_missing_file 1 "no-such\\.seg: cannot open the segment stream" replay no-such.seg)
kontur_cli_case(replay_not_a_stream 1 "square_arc\\.ngc: the header \\(64 bytes\\): it does not start with KONTURSG" replay
                examples/programs/square_arc.ngc)
kontur_cli_case(run_segment_tolerance_too_small 1 "segment tolerance 1e-12 mm is below" run examples/programs/square_arc.ngc
                --format segments --segment-tolerance 1e-12 -o -)

# kontur compress: G01 runs fitted by fewer blocks (docs/compress.md)
kontur_cli_case(compress_help 0 "Example" compress --help)
kontur_cli_case(compress_example 0 "feed blocks +719 -> [0-9]+ \\(([4-9]|[1-9][0-9]+)\\.[0-9]+ times fewer\\).*deviation +0\\.00[0-9]+ mm at most"
                compress examples/programs/dense_g01_contour.ngc -o /tmp/kontur_cli_compress.ngc --tolerance 0.01)
kontur_cli_case(compress_report 0 "" compress examples/programs/dense_g01_contour.ngc -o /tmp/kontur_cli_compress_r.ngc
                --report /tmp/kontur_cli_compress_r.json --curves arcs,conics --quiet)
kontur_cli_case(compress_missing_file 1 "no-such-program\\.ngc" compress no-such-program.ngc -o /tmp/kontur_cli_compress_missing.ngc)
kontur_cli_case(compress_zero_tolerance 1 "--tolerance 0: must be a positive number of mm" compress
                examples/programs/dense_g01_contour.ngc -o /tmp/kontur_cli_compress_tol.ngc --tolerance 0)
kontur_cli_case(compress_output_is_input 1 "dense_g01_contour\\.ngc" compress examples/programs/dense_g01_contour.ngc
                -o examples/programs/dense_g01_contour.ngc)
kontur_cli_case(compress_unknown_curve 2 "unknown curve 'ellipses'" compress examples/programs/dense_g01_contour.ngc
                -o /tmp/kontur_cli_compress_curve.ngc --curves arcs,ellipses)
kontur_cli_case(compress_bad_program 1 "knot_count\\.ngc:[0-9]+:[0-9]+: G0?6\\.2: [0-9]+ knots given" compress
                tests/data/gcode/bad/knot_count.ngc -o /tmp/kontur_cli_compress_bad.ngc)

# Unkind but valid input (issue 20): a zero-length G93 block with its own F runs; a rational G6.2 whose
# second span repeats its control point is read and run in bounded time.
kontur_cli_case(run_inverse_time_zero_length_block 0 "PASS" run tests/data/gcode/good/inverse_time_zero_length.ngc)
kontur_cli_case(check_degenerate_rational_span 0 "valid, 8 lines" check tests/data/gcode/good/degenerate_rational_span.ngc
                --quiet)
kontur_cli_case(run_degenerate_rational_span 0 "PASS" run tests/data/gcode/good/degenerate_rational_span.ngc)
