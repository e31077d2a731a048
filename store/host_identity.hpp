#pragma once
// Who is running: the host name both stores record with a session and its lock.
#include <string>

namespace palprig {

// This machine's host name, "unknown" when it cannot be read.
std::string this_host_name();

}  // namespace palprig
