#pragma once
// The one exception root of palprig. Every failure a library reports by throwing is an Error,
// and its class says what the command line does with it:
//
//   Error      something outside the input failed (a disk, a server, a device): exit 1
//              (OutputError of a file that cannot be written, the store's SqliteError and
//              PgError are Errors)
//   BadInput   a file, a field or an argument was refused before anything moved: exit 2
//              (InputError in core/input_error.hpp is the BadInput that names file, place and
//              what was expected; statistics' StatisticsError and the models' own checks of
//              what they are built from are BadInputs too)
//   RigFault   the rig faulted while running: every channel vented, exit 1
//
// A front end catches Error, prints what() as one line and exits with exit_code(); anything
// else that reaches it (std::bad_alloc, a bug's std::logic_error) is a crash to report, not an
// answer to the user. The real-time loop throws nothing: faults there are values (FaultCode).
// One exception of palprig's is no failure and never leaves its folder: experiments'
// SessionStopped unwinds a session the operator stopped (experiments/session_pacer.hpp).
#include <stdexcept>
#include <string>

namespace palprig {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  // What the command line exits with when this reaches it.
  virtual int exit_code() const noexcept { return 1; }
};

class BadInput : public Error {
 public:
  explicit BadInput(const std::string& what) : Error(what) {}
  int exit_code() const noexcept override { return 2; }
};

class RigFault : public Error {
 public:
  explicit RigFault(const std::string& what) : Error(what) {}
};

}  // namespace palprig
