#pragma once
// Standard output, checked to the last byte for every command (cli/main.cpp calls these two
// around the command, so no command checks its own printing):
//
//   - a write that fails (a full disk, /dev/full, an I/O error) is exit 1 with one line
//     "palprig: standard output: cannot write: REASON" on standard error, never a silent loss
//     behind exit 0;
//   - a closed pipe (`palprig ... | head -1`) ends quietly as Unix tools do: the process ends by
//     SIGPIPE (the shell's 141), nothing on standard error. SIGPIPE itself is ignored while a
//     command runs, so a reader that goes away never kills a process that drives air: a session
//     or a sweep goes on to its end (every trial stored, every channel vented) and only then does
//     the process end by the signal.
//
// std::cout writes through a buffer of its own (64 KiB, flushed at each newline when standard
// output is a terminal) that remembers the first error's errno: the C library forgets it once it
// has dropped the buffer it could not write, so a check at exit alone cannot name the reason.
namespace palprig::cli {

// Installs the checked buffer on std::cout and ignores SIGPIPE. Call once, first thing in main.
void check_standard_output();

// Flushes standard output and returns the process's exit code: `exit_code` when every byte was
// written; 1 (with the one line) after a failed write when the command itself succeeded; and
// after a closed pipe the process ends by SIGPIPE here, unless the command failed (its code is
// kept).
int finish_standard_output(int exit_code);

}  // namespace palprig::cli
