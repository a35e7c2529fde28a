# cmake -DSOURCE=<repository> -P docs_snippets.cmake
# docs/game-scripting.md quotes the shipped scenes: every line of its Lua excerpts (but "...") must
# be a line of the scene its section names (`scripts/scenes/<name>.lua`, first mention), leading
# and trailing blanks aside, so the worked examples cannot drift from the scenes they show.
# README.md's sections that name a scene are held to the same rule (its other Lua blocks are
# complete examples of their own: the first scene, the game-scripting sketch), and so are
# docs/porting.md's worked ports.
cmake_policy(SET CMP0007 NEW)  # keep empty lines as list elements

# The lines of a file as a list, ';' replaced by '<semicolon>' (a CMake list separator).
function(read_lines file out)
  file(READ ${file} text)
  string(REPLACE ";" "<semicolon>" text "${text}")
  string(REPLACE "\n" ";" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

function(check_excerpts doc allow_unnamed minimum)
read_lines(${SOURCE}/${doc} lines)
set(scene "")
set(in_code FALSE)
set(checked 0)
foreach(line IN LISTS lines)
  if(line MATCHES "^## ")
    set(scene "")
  elseif(NOT in_code AND scene STREQUAL "" AND line MATCHES "`(scripts/scenes/[a-z0-9_]+\\.lua)`")
    set(scene ${CMAKE_MATCH_1})
    read_lines(${SOURCE}/${scene} scene_lines)
    set(stripped "")
    foreach(s IN LISTS scene_lines)
      string(STRIP "${s}" s)
      list(APPEND stripped "${s}")
    endforeach()
  elseif(line MATCHES "^```lua")
    set(in_code TRUE)
  elseif(line MATCHES "^```")
    set(in_code FALSE)
  elseif(in_code)
    string(STRIP "${line}" quoted)
    if(NOT quoted STREQUAL "..." AND NOT quoted STREQUAL "")
      if(scene STREQUAL "")
        if(NOT allow_unnamed)
          message(FATAL_ERROR "${doc}: an excerpt outside a scene's section: ${quoted}")
        endif()
      else()
        list(FIND stripped "${quoted}" at)
        if(at LESS 0)
          message(FATAL_ERROR "${doc}: not a line of ${scene}: ${quoted}")
        endif()
        math(EXPR checked "${checked} + 1")
      endif()
    endif()
  endif()
endforeach()
if(checked LESS minimum)
  message(FATAL_ERROR "${doc}: only ${checked} excerpt lines found")
endif()
message(STATUS "${doc}: ${checked} excerpt lines match their scenes")
endfunction()

check_excerpts(docs/game-scripting.md FALSE 30)
check_excerpts(README.md TRUE 5)
# docs/porting.md's worked ports quote their scenes (the LÖVE and Box2D code they port comes first).
check_excerpts(docs/porting.md TRUE 20)
