# Compiler flags shared by every rigidlab target.
#
# -ffp-contract=off: no fused multiply-add contraction, so results are bit-identical across builds
#   that differ only in optimisation (determinism, golden hashes).
# never -ffast-math: it turns std::isnan/std::isfinite into constants and breaks the NaN firewall.
# Release builds rigidlab's own targets with -O2 and portable code generation (no -march=native), so
# the benchmark numbers are what a user of the README build gets. Given per target (it comes after
# CMAKE_CXX_FLAGS_RELEASE on the command line, so it wins) rather than by rewriting the cache's
# flags, which would change a parent project's.
# RIGIDLAB_VERIFY_CACHES (sanitizer and fuzz builds): what the step keeps between steps to save work
#   (the broad phase's shape views) is checked against a fresh computation every step.

add_library(rigidlab_options INTERFACE)
target_compile_options(rigidlab_options INTERFACE
  -Wall -Wextra -Wpedantic -ffp-contract=off -fno-fast-math $<$<CONFIG:Release>:-O2>)
if(RIGIDLAB_SANITIZE)
  target_compile_options(rigidlab_options INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(rigidlab_options INTERFACE -fsanitize=address,undefined)
  target_compile_definitions(rigidlab_options INTERFACE RIGIDLAB_VERIFY_CACHES)
endif()
