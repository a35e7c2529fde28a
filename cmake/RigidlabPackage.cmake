# `cpack -G DEB` in the build tree: a Debian package of what `cmake --install` installs, under
# /usr: the program (/usr/bin/rigidlab, which finds /usr/share/rigidlab beside it), its scripts and
# assets, the static libraries, headers and package config, and LICENSE and CHANGELOG.md in
# /usr/share/doc/rigidlab. Its run-time dependencies (SDL2, OpenGL, ...) are read from the program
# by dpkg-shlibdeps (Debian dpkg-dev, part of build-essential). docs/building.md "A Debian package".
set(CPACK_PACKAGE_NAME rigidlab)
set(CPACK_PACKAGE_VENDOR "the rigidlab authors")
set(CPACK_PACKAGE_CONTACT "the rigidlab authors <rigidlab@invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "real-time 2D rigid-body physics engine with Lua scenes and an interactive sandbox")
set(CPACK_PACKAGE_DESCRIPTION "rigidlab simulates 2D rigid bodies in double precision (C++20, Eigen). Scenes,
custom forces and sandbox mods are Lua 5.4 scripts, run headless (rigidlab run, rigidlab test) or
in an SDL2 + OpenGL sandbox that edits them live and hot-reloads them.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # rigidlab_<version>_<architecture>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# find_package(rigidlab) in a user's project also needs these (sol2 3.5 is not packaged in Debian 12).
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libeigen3-dev, liblua5.4-dev, pkg-config")
include(CPack)
