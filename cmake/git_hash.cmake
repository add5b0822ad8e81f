# Run at every build (target rcdem_git_hash): writes OUT with the source tree's git hash, with
# "-dirty" when tracked files differ from it, and rewrites the file only when that changed, so
# that only src/rcdem/core/build_info.cpp recompiles. Runs and checkpoints record this hash: read
# at configure time instead, it went stale at the first commit after `cmake`.
execute_process(COMMAND git rev-parse --short HEAD WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE hash OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT hash)
  set(hash "unknown")
else()
  execute_process(COMMAND git diff --quiet HEAD WORKING_DIRECTORY ${SRC} RESULT_VARIABLE dirty
                  ERROR_QUIET)
  if(dirty EQUAL 1)
    set(hash "${hash}-dirty")
  endif()
endif()
set(text "// Generated at build time by cmake/git_hash.cmake.\n#define RCDEM_GIT_HASH \"${hash}\"\n")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
