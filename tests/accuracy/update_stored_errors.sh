#!/bin/sh
# Rewrites tests/accuracy/stored_errors.csv from a report's accuracy.csv: the error at dt = 1/60 of
# every problem and integrator. Run it after a deliberate change of the physics, with a Release
# build, and commit the file with the change that explains it:
#   build/rigidlab accuracy --no-timing --no-long --no-plots --out /tmp/acc
#   tests/accuracy/update_stored_errors.sh /tmp/acc/accuracy.csv
set -eu
csv=${1:?usage: update_stored_errors.sh REPORT/accuracy.csv}
out=$(dirname "$0")/stored_errors.csv
awk -F, -v date="$(date -u +%Y-%m-%d)" '
  NR == 1 { next }
  !header {
    print "# Error at dt = 1/60 (err_linf of rigidlab accuracy) per reference problem and integrator: the"
    print "# regression guard of tests/accuracy (a run may be at most 5 % worse). Measured " date " at git " $22 ","
    print "# " $23 ", " $24 ". Regenerate with update_stored_errors.sh after a deliberate change."
    print "problem,integrator,err_linf_1_60"
    header = 1
  }
  $25 == 1 { print $1 "," $2 "," $12 }
' "$csv" > "$out"
echo "wrote $out ($(grep -vc '^#' "$out") lines)"
