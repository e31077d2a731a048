# Run at every build (cmake -P, from the palprig_git_commit target): writes OUT, a header with the
# git commit the program is built from, only when it changed, so that a rebuild without a new
# commit recompiles nothing. "-dirty" marks uncommitted changes to tracked files. Without git or
# outside a clone (a source tarball) it is PALPRIG_GIT_COMMIT when given, else "unknown".
#   cmake -DSOURCE_DIR=... -DOUT=.../palprig_git_commit.hpp [-DPALPRIG_GIT_COMMIT=...] -P git_commit.cmake
set(commit "unknown")
if(PALPRIG_GIT_COMMIT)
  set(commit "${PALPRIG_GIT_COMMIT}")
else()
  find_program(GIT_PROGRAM git)
  if(GIT_PROGRAM)
    execute_process(COMMAND ${GIT_PROGRAM} -C ${SOURCE_DIR} rev-parse --short=12 HEAD
      OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc ERROR_QUIET)
    if(rc EQUAL 0 AND head)
      set(commit "${head}")
      execute_process(COMMAND ${GIT_PROGRAM} -C ${SOURCE_DIR} diff-index --quiet HEAD --
        RESULT_VARIABLE dirty ERROR_QUIET)
      if(NOT dirty EQUAL 0)
        string(APPEND commit "-dirty")
      endif()
    endif()
  endif()
endif()
set(text "#pragma once\n// Written by packaging/git_commit.cmake at build time; not in the repository.\n#define PALPRIG_GIT_COMMIT \"${commit}\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
