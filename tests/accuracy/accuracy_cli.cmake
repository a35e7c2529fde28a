# cmake -DRIGIDLAB=<binary> -DWORK=<scratch dir> -P accuracy_cli.cmake
# The accuracy and stability commands' command lines: help, usage errors, the files a small report
# writes (CSV columns of docs/design/accuracy.md §5, summary, pictures when gnuplot is installed), and the
# stability report's JSON.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_checks.cmake)

run(0 accuracy --help)
expect_match("accuracy --help" "${out}" "usage: rigidlab accuracy")
run(0 stability --help)
expect_match("stability --help lists the cases" "${out}" "stiff_spring_implicit")
run(2 accuracy --integrators rk5)
expect_match("unknown integrator" "${err}" "unknown integrator 'rk5'")
run(2 accuracy --scenes no_such_problem)
run(2 stability --cases no_such_case)
run(2 accuracy --kmax 13)

# A small report: two problems, two integrators, dt = 1/30 … 1/480, 2 timed repeats.
run(0 accuracy --scenes sho,kepler --integrators semi_implicit_euler,rk4 --kmax 4 --repeats 2 --no-long --out ${WORK}/acc)
expect_match("orders printed beside the expected ones" "${out}" "sho +1\\.[0-9][0-9] \\(1\\) ok +4\\.[0-9][0-9] \\(4\\) ok")
file(STRINGS ${WORK}/acc/accuracy.csv csv)
list(LENGTH csv lines)
if(NOT lines EQUAL 21)  # header + 2 problems × 2 integrators × 5 step sizes
  message(FATAL_ERROR "accuracy.csv: ${lines} lines, expected 21")
endif()
list(GET csv 0 header)
expect_match("CSV columns (docs/design/accuracy.md §5)" "${header}"
  "^scene,integrator,dt,substeps,steps,force_evals,lua_calls,t_end,wall_s_min,wall_s_median,repeats,err_linf,err_final,err_l2,energy_drift_max,energy_drift_trend,mom_err,angmom_err,order_pairwise,status,engine_version,git_hash,build,cpu,")
list(GET csv 7 row)  # rows: sho semi ×5, sho rk4 ×5, kepler semi ×5, kepler rk4 ×5
expect_match("sho rk4 at 1/60: 606 steps, 4 force evaluations each, no Lua" "${row}" "^sho,rk4,0.016666666666666666,1,606,2424,0,10.1,")
list(GET csv 17 row)
expect_match("kepler rk4 at 1/60" "${row}" "^kepler,rk4,0.016666666666666666,1,606,2424,2424,10.1,")
file(READ ${WORK}/acc/summary.md summary)
expect_match("summary orders" "${summary}" "\\| sho \\| smooth \\| [0-9.]+ \\(1\\) PASS \\| [0-9.]+ \\(4\\) PASS \\|")
expect_match("summary stages" "${summary}" "\\| kepler \\| integrate, forces \\(Lua\\) \\| 0 \\| 0 \\|")
find_program(GNUPLOT gnuplot)
if(GNUPLOT)
  foreach(picture conv_sho.svg wp_sho.svg conv_kepler.png wp_kepler.png)
    if(NOT EXISTS ${WORK}/acc/${picture})
      message(FATAL_ERROR "${picture} was not made (gnuplot is installed)")
    endif()
  endforeach()
  file(READ ${WORK}/acc/conv_sho.svg svg)
  expect_match("the convergence picture names the fitted order" "${svg}" "rk4: p = 4\\.[0-9][0-9] \\(expected 4\\)")
endif()

# The stability report: JSON with every case run, its figures and PASS/FAIL; exit 0 when all pass.
run(0 stability --quick --cases frame_rate,stiff_spring_thresholds --out ${WORK}/stab)
file(READ ${WORK}/stab/stability.json json)
string(JSON n LENGTH "${json}" cases)
string(JSON name GET "${json}" cases 0 name)
string(JSON pass GET "${json}" cases 0 pass)
string(JSON k GET "${json}" cases 1 figures largest_stable_k_semi_implicit_euler)
if(NOT n EQUAL 2 OR NOT name STREQUAL "frame_rate" OR NOT pass STREQUAL "ON" OR NOT k EQUAL 12996)
  message(FATAL_ERROR "stability.json: ${n} cases, first ${name} pass ${pass}, semi-implicit Euler's largest stable k ${k}")
endif()
file(READ ${WORK}/stab/stability.md md)
expect_match("stability.md" "${md}" "\\| \\[frame_rate\\]\\(#frame_rate\\) \\| PASS \\|")
