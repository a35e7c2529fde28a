# Installing rigidlab so another project can use it with find_package(rigidlab):
#   <prefix>/lib/librigidlab_core.a, librigidlab_lua.a      targets rigidlab::core, rigidlab::lua
#   <prefix>/include/rigidlab/...                          the public headers
#   <prefix>/lib/cmake/rigidlab/                           rigidlabConfig.cmake and the targets
#   <prefix>/bin/rigidlab                                  the program (with the sandbox if built)
#   <prefix>/share/doc/rigidlab/LICENSE, CHANGELOG.md
#   <prefix>/share/rigidlab/scripts, assets                found at run time relative to bin/, and
#                                                          by users' programs through the package config
# The libraries are static; their private dependencies (Lua 5.4 as C++, sol2) are looked up again
# by the package config, because a static library's users link them.
include(CMakePackageConfigHelpers)

set(rigidlab_targets rigidlab_core rigidlab_options)
if(TARGET rigidlab_lua)
  list(APPEND rigidlab_targets rigidlab_lua)
endif()
install(TARGETS ${rigidlab_targets} EXPORT rigidlabTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/core/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(TARGET rigidlab_lua)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/lua/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/scripts/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rigidlab/scripts)
endif()
if(TARGET rigidlab)
  install(TARGETS rigidlab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
if(TARGET rigidlab_sandbox)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rigidlab/assets)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/rigidlab)
install(EXPORT rigidlabTargets NAMESPACE rigidlab:: DESTINATION ${config_dir})
if(TARGET rigidlab_lua)
  set(RIGIDLAB_WITH_LUA ON)
else()
  set(RIGIDLAB_WITH_LUA OFF)
endif()
set(RIGIDLAB_DATA_DIR ${CMAKE_INSTALL_DATADIR}/rigidlab)  # the package config's PACKAGE_RIGIDLAB_DATA_DIR
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/rigidlabConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/rigidlabConfig.cmake INSTALL_DESTINATION ${config_dir}
                              PATH_VARS RIGIDLAB_DATA_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rigidlabConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rigidlabConfig.cmake ${PROJECT_BINARY_DIR}/rigidlabConfigVersion.cmake
        DESTINATION ${config_dir})
