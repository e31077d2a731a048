#include "store/host_identity.hpp"

#include <unistd.h>

namespace palprig {

std::string this_host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

}  // namespace palprig
