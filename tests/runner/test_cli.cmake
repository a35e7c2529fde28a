# cmake -DRIGIDLAB=<binary> -DDIR=<tests/runner> -DWORK=<scratch dir> -P test_cli.cmake
# `rigidlab test` on a suite (tests/runner/suite, copied into WORK so that --update writes there)
# of scenes that pass, fail, error, hang, are skipped and have a golden trajectory: its lines,
# summary, exit status, JUnit XML, shards, filter, and the golden trajectory's record, match and
# mismatch.
cmake_policy(VERSION 3.20)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(COPY ${DIR}/suite DESTINATION ${WORK})
set(suite suite)
set(CLI_DIRECTORY ${WORK})  # where every command runs: the paths printed are suite/...
include(${CMAKE_CURRENT_LIST_DIR}/../cli_checks.cmake)

function(count_matches var text regex)
  string(REGEX MATCHALL "${regex}" found "${text}")
  list(LENGTH found n)
  set(${var} ${n} PARENT_SCOPE)
endfunction()

set(all_scenes suite/error_syntax.lua suite/fail_check.lua suite/golden_ball.lua suite/hang.lua
    suite/nested/deeper.lua suite/pass_ball.lua suite/skip.lua)

# Discovery: the .lua files that define a global Check, recursively and sorted; not the module.
run(0 test ${suite} --list)
string(REGEX REPLACE "\n$" "" listed "${out}")
string(REPLACE "\n" ";" listed "${listed}")
expect_equal("discovered scenes" "${listed}" "${all_scenes}")

# The whole suite: one line per scene, the summary, exit status 1. The golden file is not
# recorded yet: that is a failure telling how to record it. The hanging scene is killed after
# --timeout (6 s: long enough for the other scenes under the sanitizers on a loaded machine); a
# scene's output and Check message are shown under its line.
string(TIMESTAMP began "%s")
run(1 test ${suite} -j 3 --timeout 6 --junit ${WORK}/results/all.xml)
string(TIMESTAMP ended "%s")
expect_match("pass line" "${out}" "\nPASS +[0-9.]+ s  suite/pass_ball.lua\n")
expect_match("nested pass line" "${out}" "\nPASS +[0-9.]+ s  suite/nested/deeper.lua\n")
expect_match("fail line" "${out}" "FAIL +[0-9.]+ s  suite/fail_check.lua\n    suite/fail_check.lua:10: Check: expected the ball to float\n    \\| the ball is at y = ")
expect_match("error line" "${out}" "ERROR +[0-9.]+ s  suite/error_syntax.lua\n    suite/error_syntax.lua:[0-9]+: ")
expect_match("timeout line" "${out}" "TIMEOUT +[0-9.]+ s  suite/hang.lua\n    killed after 6 s of wall time \\(--timeout\\)")
expect_match("skip line" "${out}" "SKIP +suite/skip.lua: waiting for the new joint solver\n")
expect_match("missing golden" "${out}" "FAIL +[0-9.]+ s  suite/golden_ball.lua\n    golden trajectory suite/golden/ball.txt does not exist; record it with `rigidlab test --update suite/golden_ball.lua`")
expect_match("summary" "${out}" "\n2 passed, 2 failed, 2 errors \\(1 timed out\\), 1 skipped: 7 scenes in [0-9.]+ s\n$")
expect_match("list of the scenes that did not pass" "${out}"
             "\nnot passed:\n  ERROR +[0-9.]+ s  suite/error_syntax.lua\n  FAIL +[0-9.]+ s  suite/fail_check.lua\n  FAIL +[0-9.]+ s  suite/golden_ball.lua\n  TIMEOUT +[0-9.]+ s  suite/hang.lua\n2 passed")
math(EXPR wall "${ended} - ${began}")
if(wall GREATER 30)
  message(FATAL_ERROR "the suite took ${wall} s: the hanging scene was not killed after its 6 s")
endif()

# JUnit XML: well-formed, with the right counts and the failure messages.
file(READ ${WORK}/results/all.xml xml)
expect_match("testsuite counts" "${xml}"
             "<testsuite name=\"rigidlab test\" tests=\"7\" failures=\"2\" errors=\"2\" time=\"[0-9.]+\" skipped=\"1\"")
count_matches(ncases "${xml}" "<testcase ")
count_matches(nfailures "${xml}" "<failure ")
count_matches(nerrors "${xml}" "<error ")
count_matches(nskipped "${xml}" "<skipped>")
expect_equal("testcases" "${ncases}" "7")
expect_equal("failures" "${nfailures}" "2")
expect_equal("errors" "${nerrors}" "2")
expect_equal("skipped" "${nskipped}" "1")
expect_match("failure element" "${xml}"
             "<testcase classname=\"suite\" name=\"fail_check\" time=\"[0-9.]+\">\n      <failure type=\"failure\" message=\"suite/fail_check.lua:10: Check: expected the ball to float\">")
expect_match("timeout element" "${xml}" "name=\"hang\"[^\n]*>\n      <error type=\"timeout\" message=\"killed after 6 s")
expect_match("nested classname" "${xml}" "<testcase classname=\"suite.nested\" name=\"deeper\"")
expect_match("skip reason as the text of <skipped>" "${xml}"
             "name=\"skip\"[^\n]*>\n      <skipped>waiting for the new joint solver</skipped>")
expect_match("each scene's file as a property" "${xml}"
             "<properties>\n(      <property [^\n]*\n)*      <property name=\"suite.nested.deeper.file\" value=\"suite/nested/deeper.lua\"/>")

# The strict junit-4 schema (Jenkins' reading of JUnit XML; tests/runner/junit-4.xsd): the file
# validates, and the schema refuses what the format does not have (the attributes rigidlab wrote
# before: file on testcase, skipped on testsuites, message on skipped), so it can fail.
find_program(XMLLINT xmllint)
if(NOT XMLLINT)
  message(FATAL_ERROR "xmllint is missing: it checks the JUnit XML against tests/runner/junit-4.xsd (Debian libxml2-utils; cmake/install_deps.sh installs it)")
endif()
set(schema ${DIR}/junit-4.xsd)
function(validate label file expected_status)
  execute_process(COMMAND ${XMLLINT} --noout --schema ${schema} ${file} RESULT_VARIABLE status ERROR_VARIABLE perr)
  if(expected_status EQUAL 0)
    expect_equal("${label}: valid junit-4 (${perr})" "${status}" "0")
  elseif(status EQUAL 0)
    message(FATAL_ERROR "${label}: the junit-4 schema accepted it")
  endif()
endfunction()
validate("the suite's JUnit XML" ${WORK}/results/all.xml 0)
function(validate_with_extra label from to)
  string(REPLACE "${from}" "${to}" bad "${xml}")
  if(bad STREQUAL xml)
    message(FATAL_ERROR "${label}: '${from}' is not in the JUnit XML")
  endif()
  file(WRITE ${WORK}/results/bad.xml "${bad}")
  validate("${label}" ${WORK}/results/bad.xml 1)
endfunction()
validate_with_extra("file on testcase" "name=\"pass_ball\"" "name=\"pass_ball\" file=\"suite/pass_ball.lua\"")
validate_with_extra("skipped on testsuites" "<testsuites name=\"rigidlab test\"" "<testsuites name=\"rigidlab test\" skipped=\"1\"")
validate_with_extra("message on skipped" "<skipped>" "<skipped message=\"waiting\">")

# Shards: every scene in exactly one shard, position i (from 0) in shard (i mod N) + 1.
set(union "")
foreach(k 1 2 3)
  run(0 test ${suite} --shard ${k}/3 --list)
  string(REGEX REPLACE "\n$" "" shard "${out}")
  string(REPLACE "\n" ";" shard "${shard}")
  set(expected "")
  set(i 0)
  foreach(scene ${all_scenes})
    math(EXPR owner "${i} % 3 + 1")
    if(owner EQUAL k)
      list(APPEND expected ${scene})
    endif()
    math(EXPR i "${i} + 1")
  endforeach()
  expect_equal("shard ${k}/3" "${shard}" "${expected}")
  foreach(scene ${shard})
    if(scene IN_LIST union)
      message(FATAL_ERROR "${scene} is in two shards")
    endif()
  endforeach()
  list(APPEND union ${shard})
endforeach()
list(SORT union)
expect_equal("union of the shards" "${union}" "${all_scenes}")
# A shard runs only its scenes: 2/3 is fail_check and pass_ball.
run(1 test ${suite} --shard 2/3)
expect_match("shard 2/3 summary" "${out}" "1 passed, 1 failed, 0 errors, 0 skipped: 2 scenes in")
# More shards than scenes: an empty shard passes.
run(0 test ${suite} --shard 9/9)
expect_match("empty shard" "${out}" "shard 9/9 has no scenes \\(7 in all\\)")

# --filter: a substring, or a glob over the whole path.
run(0 test ${suite} --filter pass_ --list)
expect_equal("substring filter" "${out}" "suite/pass_ball.lua\n")
run(0 test ${suite} --filter "*/nested/*.lua" --list)
expect_equal("glob filter" "${out}" "suite/nested/deeper.lua\n")
run(0 test ${suite} --filter "suite/p*" -j1)
expect_match("filtered run" "${out}" "1 passed, 0 failed, 0 errors, 0 skipped: 1 scene in")
run(1 test ${suite} --filter nothing_matches)
expect_match("a filter that matches nothing" "${err}" "--filter 'nothing_matches' matches none of the 7 scenes")

# Golden trajectory: --update records it beside the scene, a second run matches it bit for bit.
run(0 test ${suite}/golden_ball.lua --update)
expect_match("update line" "${out}" "PASS +[0-9.]+ s  suite/golden_ball.lua: golden trajectory written to suite/golden/ball.txt")
file(STRINGS ${WORK}/suite/golden/ball.txt golden)
list(FILTER golden EXCLUDE REGEX "^#")
list(SUBLIST golden 0 4 header)
expect_equal("golden header" "${header}" "scene golden_ball.lua;dt 0.01;steps 100;every 5")
list(FILTER golden INCLUDE REGEX "^sample ")
list(LENGTH golden nsamples)
expect_equal("samples: step 0, then every 5 of 100 steps" "${nsamples}" "21")
file(STRINGS ${WORK}/suite/golden/ball.txt ball_lines REGEX "^30 2 ")
expect_match("a body line: step uid x y angle vx vy omega name" "${ball_lines}"
             "^30 2 [-0-9.e+]+ [-0-9.e+]+ [-0-9.e+]+ [-0-9.e+]+ [-0-9.e+]+ [-0-9.e+]+ ball$")  # no {6} in CMake
run(0 test ${suite} --filter golden)
expect_match("golden match" "${out}" "PASS +[0-9.]+ s  suite/golden_ball.lua\n")

# A perturbed run: the first diverging body and step, both trajectories written for a diff.
file(READ ${WORK}/suite/golden_ball.lua source)
string(REPLACE "local PERTURB = false" "local PERTURB = true" perturbed "${source}")
file(WRITE ${WORK}/suite/golden_ball.lua "${perturbed}")
run(1 test ${suite} --filter golden --diff-dir diffs --junit ${WORK}/golden.xml)
expect_match("divergence" "${out}"
             "golden trajectory suite/golden/ball.txt: body 2 \"ball\" diverged first at step 30 \\(t = 0.3[0-9]* s\\): x is [-0-9.e]+, expected [-0-9.e]+ \\(off by 1e-09\\) \\(tolerance 0: bit for bit\\)")
expect_match("diff command" "${out}" "both trajectories are in diffs/suite/golden_ball/: diff -u diffs/suite/golden_ball/expected.txt diffs/suite/golden_ball/actual.txt")
foreach(f expected actual)
  if(NOT EXISTS ${WORK}/diffs/suite/golden_ball/${f}.txt)
    message(FATAL_ERROR "no ${f}.txt in diffs/suite/golden_ball/")
  endif()
endforeach()
file(READ ${WORK}/diffs/suite/golden_ball/expected.txt expected_text)
file(READ ${WORK}/suite/golden/ball.txt golden_text)
expect_equal("expected.txt is the golden file" "${expected_text}" "${golden_text}")
file(STRINGS ${WORK}/diffs/suite/golden_ball/actual.txt actual_25 REGEX "^25 2 ")
file(STRINGS ${WORK}/suite/golden/ball.txt golden_25 REGEX "^25 2 ")
expect_equal("before the nudge the runs agree" "${actual_25}" "${golden_25}")
file(READ ${WORK}/golden.xml xml)
validate("the golden run's JUnit XML" ${WORK}/golden.xml 0)
expect_match("golden failure in the XML" "${xml}" "<failure type=\"failure\" message=\"golden trajectory suite/golden/ball.txt: body 2 &quot;ball&quot; diverged first at step 30")
# Within a tolerance the nudge passes.
string(REPLACE "golden_every = 5" "golden_every = 5, golden_tolerance = 1e-6" tolerant "${perturbed}")
file(WRITE ${WORK}/suite/golden_ball.lua "${tolerant}")
run(0 test ${suite} --filter golden)

# The scene fields are validated where the scene table is read: `rigidlab check` on a scene whose
# table is `settings` fails with a message that matches `regex`.
function(expect_scene_error name settings regex)
  file(WRITE ${WORK}/${name}.lua "scene = { ${settings} }\nfunction PopulateWorld(world) end\n")
  run(1 check ${WORK}/${name}.lua)
  expect_match("scene = { ${settings} }" "${err}" "${name}.lua:1: scene: ${regex}")
endfunction()
expect_scene_error(bad_golden "golden = '../up'" "golden must be a file name of letters, digits")
expect_scene_error(bad_every "golden_every = 5" "golden_every needs scene.golden")
expect_scene_error(bad_tolerance "golden = 'g', golden_tolerance = -1" "golden_tolerance must be >= 0")
expect_scene_error(bad_typo "goldn = 'g'" "unknown option 'goldn' \\(did you mean 'golden'\\?\\)")
expect_scene_error(bad_skip "skip = true" "skip must be a string")

# Inputs over their size limits (issue 32, docs/security.md "Files"): each is refused before it is
# read, naming the file, its size and the limit.
set(big ${WORK}/big)
file(MAKE_DIRECTORY ${big}/golden ${WORK}/modules)
string(REPEAT "x" 5000000 filler)
# A 5 MB scene that discovery finds is not read by the runner: it is run, and its refusal reported.
file(WRITE ${big}/huge.lua "function Check(world) end\nfunction PopulateWorld(world) end\n-- ${filler}\n")
run(1 test big/huge.lua)
expect_match("a 5 MB scene" "${out}" "ERROR .*big/huge.lua")
expect_match("a 5 MB scene" "${out}" "the file is 5000064 bytes, more than the limit of 4 MiB for a scene file")
run(1 run big/huge.lua)
expect_match("a 5 MB scene run" "${err}" "big/huge.lua: the file is 5000064 bytes, more than the limit of 4 MiB for a scene file")
file(REMOVE ${big}/huge.lua)
# A 5 MB module.
file(WRITE ${WORK}/modules/heavy.lua "-- ${filler}\nreturn 1\n")
file(WRITE ${WORK}/modules/uses_heavy.lua "local heavy = require 'heavy'\nfunction PopulateWorld(world) end\n")
run(1 run modules/uses_heavy.lua --steps 0)
expect_match("a 5 MB module" "${err}" "uses_heavy.lua:1: require: modules/heavy.lua: the file is 5000013 bytes, more than the limit of 4 MiB for a module file")
# A 400 MB golden trajectory (a hole): refused unread; it took rigidlab test past 2 GB in 13 s.
file(WRITE ${big}/wide.lua "scene = { golden = 'wide', duration = 0.1 }\nfunction PopulateWorld(world) world:add_circle{ radius = 1 } end\nfunction Check(world) end\n")
file(WRITE ${big}/golden/wide.txt "")
execute_process(COMMAND truncate -s 400M ${big}/golden/wide.txt RESULT_VARIABLE truncated)
expect_equal("truncate" "${truncated}" "0")
run(1 test big)
expect_match("a 400 MB golden" "${out}" "cannot read the golden trajectory: big/golden/wide.txt: the file is 419430400 bytes, more than the limit of 64 MiB for a golden trajectory")
# A run whose trajectory would pass the limit stops recording it (4 000 bodies sampled every step for
# 180 steps: few enough add_box calls for the 1 s budget under the sanitizers).
file(WRITE ${big}/wide.lua "scene = { golden = 'wide', golden_every = 1, duration = 3 }\nfunction PopulateWorld(world)\n  for i = 1, 4000 do world:add_box{ width = 0.5, height = 0.5, position = {i, 0}, static = true } end\nend\nfunction Check(world) end\n")
file(REMOVE ${big}/golden/wide.txt)
run(1 test big --update)
expect_match("a trajectory past the limit" "${out}" "ERROR .*big/wide.lua.*scene.golden: the golden trajectory would be larger than the limit of 64 MiB \\([0-9]+ samples by step [0-9]+ of 180\\); sample less often")
if(EXISTS ${big}/golden/wide.txt)
  message(FATAL_ERROR "a golden trajectory past the limit was written")
endif()

# Usage errors.
run(0 test --help)
expect_match("help" "${out}" "--shard K/N")
run(2 test ${suite} --shard 0/3)
run(2 test ${suite} --shard 4/3)
run(2 test ${suite} --shard 1-3)
run(2 test ${suite} --timeout -1)
run(2 test ${suite} -j 0)
run(2 test ${suite} --bogus)
run(2 test ${WORK}/no_such_folder)
message(STATUS "rigidlab test: all checks passed")
