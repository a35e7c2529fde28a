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
foreach(scene large_pyramid many_pyramids joint_grid ragdolls smash spinner tumbler)
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
