#!/bin/sh
# A stand-in for a peer program (bench_cli.cmake): one JSON line in the format of
# engine/peers/scenes.h with fixed times, so that the comparison's columns and ratios can be
# checked without the engines. Box2D 2.4.1 takes 1 ms a step, Chipmunk 0.5, "Box2D v3" 2 on one
# thread and 4 on two; on the pyramids each takes a nanosecond, faster than rigidlab can be, and on
# rain a second, slower than rigidlab can be; massratio never ends (for --peer-timeout).
ms=2
case "$(basename "$0")" in box2d_bench) ms=1 ;; chipmunk_bench) ms=0.5 ;; esac
case " $* " in *" --workers=2"*) ms=4 ;; esac
[ "$1" = pyramid ] && ms=1e-6
[ "$1" = rain ] && ms=1000
[ "$1" = massratio ] && exec sleep 60
printf '{"engine": "fake", "scene": "%s", "n": 10, "ms_median": %s, "metrics": {"toppled": false, "max_disp_m": 0.125}}\n' "$1" "$ms"
