# cmake -DRIGIDLAB=<binary> -DVERSION=<project version> -DBUILD_TYPE=<config> -DSOURCE=<tree> -P version_and_typos.cmake
# `rigidlab --version` and `-V`: the CMake project's version, the build type and the commit of the
# tree it was built from; mistyped commands, options and scenes get a suggestion ("did you mean"),
# far-off words none, and every message names the program once.
include(${CMAKE_CURRENT_LIST_DIR}/../cli_checks.cmake)

# The commit line: the tree's own when it is a git checkout of its own (cmake/RigidlabVersion.cmake).
set(commit_part "")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE} rev-parse --show-toplevel OUTPUT_VARIABLE top
                  OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE top_status ERROR_QUIET)
  if(top_status EQUAL 0)
    file(REAL_PATH "${top}" top)
    file(REAL_PATH "${SOURCE}" source)
  endif()
  if(top_status EQUAL 0 AND top STREQUAL source)
    execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE} rev-parse --short=12 HEAD OUTPUT_VARIABLE head
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
    set(commit_part ", commit ${head}(, modified)?")
  endif()
endif()
string(REPLACE "." "\\." version_regex "${VERSION}")
foreach(flag --version -V)
  run(0 ${flag})
  expect_match("rigidlab ${flag}" "${out}" "^rigidlab ${version_regex} \\(${BUILD_TYPE} build${commit_part}\\)\n$")
  expect_equal("rigidlab ${flag}: standard error" "${err}" "")
endforeach()
run(0 --help)
expect_match("help lists --version" "${out}" "rigidlab --version, -V")

# typo(ARGS... EXPECTED): exit status 2 and standard error starting with EXPECTED (a regex),
# the program named once.
function(typo)
  list(POP_BACK ARGN expected)
  run(2 ${ARGN})
  expect_match("rigidlab ${ARGN}" "${err}" "^rigidlab: ${expected}\n\\(see `rigidlab help`\\)\n$")
endfunction()
typo(--verison "unknown option --verison \\(did you mean --version\\?\\)")
typo(-v "unknown option -v \\(did you mean -V\\?\\)")
typo(-version "unknown option -version \\(did you mean --version\\?\\)")
typo(--frame 3 "unknown option --frame \\(did you mean --frames\\?\\)")
typo(--xyzzy "unknown option --xyzzy")
typo(-x "unknown option -x")
typo(tset "unknown command 'tset' \\(did you mean 'test'\\?\\)")
typo(rnu x.lua "unknown command 'rnu' \\(did you mean 'run'\\?\\)")
typo(stabilty "unknown command 'stabilty' \\(did you mean 'stability'\\?\\)")
typo(chekc x.lua "unknown command 'chekc' \\(did you mean 'check'\\?\\)")
typo(foo "unknown command 'foo'")
typo(run --tmie 3 x.lua "run: unknown option --tmie \\(did you mean --time\\?\\)")
typo(test --jbos 2 "test: unknown option --jbos \\(did you mean --jobs\\?\\)")
typo(bench --compar "bench: unknown option --compar \\(did you mean --compare\\?\\)")
typo(bench stak10 "bench: unknown scene 'stak10' \\(did you mean 'stack10'\\?\\) \\(see rigidlab bench --help\\)")
typo(--frames "--frames needs a value")
