# Every dependency comes from a Debian 12 package (cmake/install_deps.sh installs them); nothing is
# downloaded at build time. Each is wrapped in an imported target.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Threads REQUIRED)  # the world's worker threads (WorldDef::threads)

if(RIGIDLAB_LUA)
  find_package(PkgConfig REQUIRED)
  # Debian's Lua 5.4 compiled as C++ (C-linkage symbols): a Lua error is a C++ exception, so it
  # unwinds C++ frames with their destructors instead of longjmp-ing over them (docs/design/reliability.md
  # §1.4). sol2 is configured to match in engine/lua/CMakeLists.txt.
  pkg_check_modules(LUA REQUIRED IMPORTED_TARGET lua5.4-c++)
  find_package(sol2 3.5 REQUIRED)
endif()

if(RIGIDLAB_SANDBOX)
  find_package(SDL2 REQUIRED)
  find_package(OpenGL REQUIRED COMPONENTS OpenGL)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
endif()

if(RIGIDLAB_TESTS)
  find_package(doctest REQUIRED)
endif()
