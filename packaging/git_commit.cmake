# Run at every build (cmake -P, from the palprig_git_commit target): writes OUT, a one-function
# source file with the git commit the program is built from, only when it changed, so that a
# rebuild without a new commit recompiles nothing and a new commit recompiles only this file. "-dirty" marks uncommitted changes to tracked files. Without git or
# outside a clone (a source tarball) it is PALPRIG_GIT_COMMIT when given, else "unknown".
#   cmake -DSOURCE_DIR=... -DOUT=.../palprig_git_commit.cpp [-DPALPRIG_GIT_COMMIT=...] -P git_commit.cmake
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
# No include: this file compiles in a moment (cli/commands.hpp declares the function).
set(text "// Written by packaging/git_commit.cmake at build time; not in the repository.\nnamespace palprig::cli {\nconst char* git_commit() noexcept { return \"${commit}\"; }\n}  // namespace palprig::cli\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
