# cmake -DRIGIDLAB=<binary> -P bench_cli.cmake
# `rigidlab bench` builds every scene of Box2D v3's suite as that suite does (body and joint
# counts, the scene's own edits between steps), runs it, and reports the figures the comparison
# reads; and its command line refuses what it cannot do. Two steps per scene: a check of the
# scenes, not a benchmark.
include(${CMAKE_CURRENT_LIST_DIR}/../cli_checks.cmake)

function(expect_metric scene steps key expected)
  run(0 bench ${scene} --steps ${steps} --reps 1 --json)
  string(JSON value GET "${out}" metrics ${key})
  if(NOT "${value}" STREQUAL "${expected}")
    message(FATAL_ERROR "bench ${scene}: ${key} = ${value}, expected ${expected}\n${out}")
  endif()
endfunction()

run(0 bench --help)
foreach(scene large_pyramid many_pyramids joint_grid ragdolls smash spinner tumbler compounds junkyard washer)
  if(NOT "${out}" MATCHES "  ${scene} ")
    message(FATAL_ERROR "bench --help does not list ${scene}")
  endif()
endforeach()

expect_metric(large_pyramid 2 bodies 5050)
expect_metric(many_pyramids 2 bodies 22000)
expect_metric(joint_grid 2 bodies 9993)      # 10 000 discs, 7 of them static
expect_metric(joint_grid 2 joints 19794)     # Box2D's 19 800 less the 6 between static discs
expect_metric(smash 2 awake_at_end 1)        # the wall is created asleep: only the heavy box moves
expect_metric(spinner 2 bodies 6077)
expect_metric(spinner 2 joints 1)
expect_metric(tumbler 2 bodies 2026)
# compounds, junkyard and washer: one run each, several figures. Created awake, none has landed
# after 2 steps (nothing touches, every figure is its exact value) and none is out of its container.
function(expect_metrics scene steps)
  run(0 bench ${scene} --steps ${steps} --reps 1 --json)
  set(pairs ${ARGN})
  while(pairs)
    list(POP_FRONT pairs key expected)
    string(JSON value GET "${out}" metrics ${key})
    if(NOT "${value}" STREQUAL "${expected}")
      message(FATAL_ERROR "bench ${scene}: ${key} = ${value}, expected ${expected}\n${out}")
    endif()
  endwhile()
endfunction()
expect_metrics(compounds 2 bodies 3000 awake_at_end 3000 joints 0 escaped 0 max_penetration_m 0)
expect_metrics(junkyard 2 bodies 8000 awake_at_end 8000 escaped 0 max_penetration_m 0)
expect_metrics(washer 2 bodies 8100 awake_at_end 8100 escaped 0 max_penetration_m 0)
# Ragdolls: a column of 5 groups of 5 (11 bones, 10 joints each) every 8 steps, from step 0.
expect_metric(ragdolls 9 bodies 550)
expect_metric(ragdolls 9 joints 500)

# 100 balls, each first impact located inside its step in the first second (the second ones come
# after 1.17 s); once per step, none.
expect_metric(balls100 60 impacts_located 100)
run(0 bench balls100 --steps 60 --reps 1 --json --impacts per_step)
string(JSON value GET "${out}" metrics impacts_located)
if(NOT value EQUAL 0)
  message(FATAL_ERROR "bench balls100 --impacts per_step: ${value} impacts located, expected 0")
endif()
run(2 bench balls100 --impacts sometimes)

run(2 bench no_such_scene)
run(2 bench stack10 --steps 0)
run(2 bench stack10 --v3-threads 0)
run(2 bench stack10 --v3 /nonexistent/bench_v3)
# --substeps: one count, or a list for the comparison with Box2D v3 only.
run(2 bench stack10 --substeps 0)
run(2 bench stack10 --substeps 8,x)
run(2 bench stack10 --substeps 8,4)
run(0 bench stack10 --substeps 4 --steps 2 --reps 1 --json)
string(JSON value GET "${out}" settings substeps)
if(NOT value EQUAL 4)
  message(FATAL_ERROR "bench --substeps 4: the run reports ${value} sub-steps\n${out}")
endif()

# --compare: rigidlab alternated with every peer program, one row per configuration. The fake
# peers (fake_peers/) take 1 ms a step (Box2D 2.4.1), 0.5 (Chipmunk), 2 and 4 (Box2D v3 on 1 and
# 2 threads), so each ratio is rigidlab's time over a known figure.
set(fake ${CMAKE_CURRENT_LIST_DIR}/fake_peers)
run(0 bench stack10 --compare --peers ${fake} --v3 ${fake}/fake_engine.sh --reps 1 --steps 5 --json)
string(JSON peers LENGTH "${out}" peers)
expect_equal("bench --compare --v3: peer configurations" "${peers}" 4)
string(JSON ms GET "${out}" ms)
set(expected_engines "Box2D v3, 1 thread" "Box2D v3, 2 threads" "Box2D 2.4.1" "Chipmunk 7")
set(expected_ms 2 4 1 0.5)
foreach(i RANGE 3)
  list(GET expected_engines ${i} engine)
  list(GET expected_ms ${i} peer_ms)
  string(JSON value GET "${out}" peers ${i} engine)
  expect_equal("bench --compare: peer ${i}" "${value}" "${engine}")
  string(JSON value GET "${out}" peers ${i} ms)
  expect_equal("bench --compare: ${engine}'s time" "${value}" "${peer_ms}")
  string(JSON value GET "${out}" peers ${i} metrics max_disp_m)
  expect_equal("bench --compare: ${engine}'s figures" "${value}" 0.125)
endforeach()
string(JSON value GET "${out}" peers 2 ratio)
expect_equal("bench --compare: rigidlab / Box2D 2.4.1 at 1 ms" "${value}" "${ms}")
# A peer more than 5 times slower than rigidlab (1 s a step on rain) runs in the first round only;
# faster ones (a nanosecond on the pyramids) in every round.
foreach(case "pyramid20;2" "rain1000;1")
  list(GET case 0 scene)
  list(GET case 1 rounds)
  run(0 bench ${scene} --compare --peers ${fake} --reps 2 --steps 2 --json)
  foreach(i RANGE 1)
    string(JSON value GET "${out}" peers ${i} rounds)
    expect_equal("bench ${scene} --compare --reps 2: rounds of peer ${i}" "${value}" ${rounds})
  endforeach()
endforeach()
run(0 bench stack10 --compare --peers ${fake} --reps 1 --steps 5 --substeps 8,4)
expect_match("bench --compare" "${out}" "rigidlab, 4 sub-steps")
expect_match("bench --compare" "${out}" "Chipmunk 7 +0.500 \\[0.500-0.500\\] +rigidlab/peer [0-9.]+, [0-9.]+ +stands, disp 0.125")
run(0 bench springs --compare --peers ${fake} --reps 1 --steps 5)
expect_match("bench --compare, a scene the peers lack" "${out}" "springs: the peers have no such scene")
# A peer run past --peer-timeout is stopped and reported as at least the limit over its steps.
run(0 bench massratio --compare --peers ${fake} --reps 2 --steps 10 --peer-timeout 1 --json)
string(JSON value GET "${out}" peers 0 timed_out_s)
expect_equal("bench --peer-timeout 1: Box2D 2.4.1 stopped after" "${value}" 1)
string(JSON value GET "${out}" peers 1 ms_at_least)
expect_equal("bench --peer-timeout 1, 10 steps: Chipmunk took at least (ms a step)" "${value}" 100)
run(0 bench massratio --compare --peers ${fake} --reps 1 --steps 10 --peer-timeout 1)
expect_match("bench --peer-timeout" "${out}" "Chipmunk 7 +> 100.000 \\(stopped after 1 s\\) +rigidlab/peer < [0-9.]+")
run(2 bench stack10 --peer-timeout 5)
run(2 bench stack10 --compare --peers /nonexistent)
run(2 bench stack10 --peers ${fake})

# --compare installs nothing: without the peers' packages (here hidden from the compiler by
# -nostdinc, whether installed or not) it names them and the command that installs them, exits
# with 1, and never calls apt-get or sudo (stand-ins on PATH record any call).
set(fakebin ${CMAKE_CURRENT_BINARY_DIR}/compare_no_install_bin)
file(REMOVE_RECURSE ${fakebin})
foreach(tool apt-get apt sudo dpkg)
  file(WRITE ${fakebin}/${tool} "#!/bin/sh\necho \"${tool} $*\" >> '${fakebin}/called'\nexit 1\n")
  file(CHMOD ${fakebin}/${tool} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E env "PATH=${fakebin}:$ENV{PATH}" "CXX=g++ -nostdinc"
                        ${RIGIDLAB} bench stack10 --compare --peers ${CMAKE_CURRENT_LIST_DIR}/../../engine/peers --reps 1 --steps 2
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_equal("bench --compare without the peers' packages: exit status (${err})" "${status}" 1)
expect_match("bench --compare names the missing packages" "${err}" "missing Debian packages: libbox2d-dev libchipmunk-dev\n")
expect_match("bench --compare gives the command" "${err}" "install them with: sudo apt-get install libbox2d-dev libchipmunk-dev\n")
expect_match("bench --compare says nothing was installed" "${err}" "nothing was installed")
if(EXISTS ${fakebin}/called)
  file(READ ${fakebin}/called called)
  message(FATAL_ERROR "bench --compare ran: ${called}")
endif()

# CPU time per step beside the wall time: positive, and on one thread no more than the wall time
# (it is read inside the wall time's interval).
run(0 bench springs --steps 20 --reps 1 --threads 1 --json)
string(JSON cpu GET "${out}" cpu_ms_median)
string(JSON wall GET "${out}" ms_median)
if(NOT cpu GREATER 0 OR cpu GREATER wall)
  message(FATAL_ERROR "bench springs: cpu_ms_median ${cpu}, ms_median ${wall}\n${out}")
endif()
