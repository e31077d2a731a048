#pragma once
// What the user running palprig lacks to drive the rig without root, for `palprig rt-check`:
// the palprig group (on the machine, in the user's groups, and in this login's groups: pam and
// the session give a new membership only at the next login), the package's limits.d file (the
// real-time priority and locked memory of that group) and read-write access to the rig's devices
// (comedi cards, pen tablets as udev marks them). The real-time limits themselves are
// probe_system()'s (rt_readiness.hpp); this adds who may have them and the devices.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

#include "diagnostics/rt_readiness.hpp"

namespace palprig {

// Where to look and who is asking: the defaults are this machine and this process.
struct RigUserProbe {
  std::string group = "palprig";
  std::filesystem::path limits_file = "/etc/security/limits.d/palprig.conf";
  std::filesystem::path dev_dir = "/dev";                  // comedi* here, input/event* below
  std::filesystem::path udev_data_dir = "/run/udev/data";  // c13:N says E:ID_INPUT_TABLET=1
  uid_t uid = 0;
  std::string user;
  std::vector<gid_t> login_groups;  // this process's groups (getgroups and its gid)
  std::vector<gid_t> member_of;     // what the group database gives the user (getgrouplist)
};

// The probe for this process: its uid, user name and both group lists.
RigUserProbe this_process_probe();

// Whether uid with these groups may read and write a file of this owner, group and mode (the
// permission bits only; root may always).
bool may_read_write(uid_t uid, const std::vector<gid_t>& groups, uid_t owner, gid_t group, mode_t mode) noexcept;

// Findings (topic "user", "limits", "devices") and the advice lines for what is missing.
struct RigUserAccess {
  std::vector<Finding> findings;
  std::vector<std::string> advice;
};
RigUserAccess check_rig_user_access(const RigUserProbe& probe);

}  // namespace palprig
