# cmake -DRIGIDLAB=<binary> -P bench_probes.cmake
# `rigidlab bench queries` and `rigidlab bench events` measure something after each step (queries,
# event delivery) instead of the step: one step of each, so that the probes cannot rot. Their
# counts are checked, never their times (timings are benchmarks, not tests).
include(${CMAKE_CURRENT_LIST_DIR}/../cli_checks.cmake)

function(metric scene key)
  run(0 bench ${scene} --steps 1 --reps 1 --json)
  string(JSON value GET "${out}" metrics ${key})
  set(value "${value}" PARENT_SCOPE)
endfunction()

# The Lua calls per step of `steps` steps of a scene.
function(expect_lua_calls scene steps expected what)
  run(0 bench ${scene} --steps ${steps} --reps 1 --json)
  string(JSON value GET "${out}" lua_calls_per_step)
  expect_equal("${scene}: Lua calls per step (${what})" "${value}" ${expected})
endfunction()

run(0 bench --help)
expect_match("bench --help" "${out}" "  queries ")
expect_match("bench --help" "${out}" "  events ")

# One step: 1000 rays and 200 box queries, each timed; 10 000 bodies about 1 m apart, so a 9.5 m
# box meets about (9.5 + 0.5)² = 100 shapes and nearly every 20 m ray hits one.
metric(queries ray_samples)
expect_equal("queries: rays timed" "${value}" 1000)
metric(queries box_samples)
expect_equal("queries: box queries timed" "${value}" 200)
metric(queries box_shapes_mean)
if(value LESS 90 OR value GREATER 110)
  message(FATAL_ERROR "queries: a 9.5 m box found ${value} shapes, expected about 100")
endif()
metric(queries ray_hit_fraction)
if(value LESS 0.9)
  message(FATAL_ERROR "queries: ${value} of the rays hit, expected nearly all")
endif()

# One step: the 1000 balls start 1 mm into the floor, 1000 begin events, each given to the hook.
metric(events begin_events_per_step)
expect_equal("events: begin events" "${value}" 1000)
expect_lua_calls(events 1 1001 "1000 OnContactBegin and OnStep")

# One step of 1000 resting contacts: a call of the floor's pre_solve function for each, none
# without it (bench_command.cpp prints the difference of their step times per call).
expect_lua_calls(pre_solve 1 1000 "one per contact")
expect_lua_calls(pre_solve_off 1 0 "none")

# Two steps of the balls put onto the floor and off it: ShouldCollide is asked once per ball when
# its box begins to overlap the floor's (the first step; on the second the balls are away), besides
# the two OnStep calls; none without the hook.
expect_lua_calls(should_collide 2 501 "(1000 ShouldCollide + 2 OnStep) / 2")
expect_lua_calls(should_collide_off 2 1 "OnStep")
