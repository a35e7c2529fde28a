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

# RIGIDLAB_PCH: Eigen and the standard headers that nearly every file of the core, the program and
# the C++ tests includes (through rigidlab/math.h), parsed once per target instead of once per file.
# Measured on one core file: 1.6 -> 0.75 s of compile time (error.cpp), 3.3 -> 2.25 s (shape.cpp).
# A fresh build (CI's three builds) gains; sol2's headers are not precompiled, because a Lua-layer
# file spends its time instantiating sol2's templates, not parsing them (lua_joint.cpp: 5.5 s either
# way). Off by default when a compiler launcher such as ccache is set: ccache does not cache files
# built with a precompiled header unless configured for it, and its cache already spares the work.
# GCC only (the Release and sanitizer builds): GCC parses the header instead when a precompiled one
# does not fit, where clang (the fuzz build) stops with an error.
if(CMAKE_CXX_COMPILER_LAUNCHER OR NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(rigidlab_pch_default OFF)
else()
  set(rigidlab_pch_default ON)
endif()
option(RIGIDLAB_PCH "Precompile Eigen and the standard headers for rigidlab's own targets" ${rigidlab_pch_default})

# rigidlab_precompile_headers(TARGET [HEADER...]): the list above and the extra headers given.
function(rigidlab_precompile_headers target)
  if(RIGIDLAB_PCH)
    target_precompile_headers(${target} PRIVATE ${ARGN} <Eigen/Core> <algorithm> <cmath> <cstdint> <functional> <memory>
                              <optional> <string> <string_view> <vector>)
  endif()
endfunction()
