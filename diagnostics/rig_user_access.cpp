#include "diagnostics/rig_user_access.hpp"

#include <grp.h>
#include <pwd.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <system_error>

namespace palprig {

namespace {

namespace fs = std::filesystem;

bool has(const std::vector<gid_t>& groups, gid_t g) {
  return std::find(groups.begin(), groups.end(), g) != groups.end();
}

// "/dev/input/event3" -> "c13:67" (the udev database's name of a character device).
std::string udev_name(const struct stat& st) {
  return "c" + std::to_string(major(st.st_rdev)) + ":" + std::to_string(minor(st.st_rdev));
}

bool udev_says_tablet(const fs::path& udev_data_dir, const struct stat& st) {
  std::ifstream in(udev_data_dir / udev_name(st));
  std::string line;
  while (std::getline(in, line))
    if (line == "E:ID_INPUT_TABLET=1") return true;
  return false;
}

std::string group_name(gid_t g) {
  const struct group* gr = ::getgrgid(g);
  return gr ? gr->gr_name : std::to_string(g);
}

}  // namespace

RigUserProbe this_process_probe() {
  RigUserProbe p;
  p.uid = ::getuid();
  const gid_t gid = ::getgid();
  if (const struct passwd* pw = ::getpwuid(p.uid)) {
    p.user = pw->pw_name;
    int n = 64;
    std::vector<gid_t> groups(static_cast<std::size_t>(n));
    if (::getgrouplist(pw->pw_name, pw->pw_gid, groups.data(), &n) < 0) {
      groups.resize(static_cast<std::size_t>(n));
      ::getgrouplist(pw->pw_name, pw->pw_gid, groups.data(), &n);
    }
    groups.resize(static_cast<std::size_t>(std::max(n, 0)));
    p.member_of = groups;
  } else {
    p.user = std::to_string(p.uid);
  }
  const int count = ::getgroups(0, nullptr);
  std::vector<gid_t> login(static_cast<std::size_t>(std::max(count, 0)));
  if (count > 0) login.resize(static_cast<std::size_t>(std::max(::getgroups(count, login.data()), 0)));
  login.push_back(gid);
  p.login_groups = login;
  return p;
}

bool may_read_write(uid_t uid, const std::vector<gid_t>& groups, uid_t owner, gid_t group, mode_t mode) noexcept {
  if (uid == 0) return true;
  if (owner == uid) return (mode & S_IRUSR) && (mode & S_IWUSR);
  if (has(groups, group)) return (mode & S_IRGRP) && (mode & S_IWGRP);
  return (mode & S_IROTH) && (mode & S_IWOTH);
}

RigUserAccess check_rig_user_access(const RigUserProbe& p) {
  RigUserAccess a;
  auto add = [&a](Finding::Level level, const char* topic, std::string text) {
    a.findings.push_back({level, topic, std::move(text)});
  };
  const struct group* gr = ::getgrnam(p.group.c_str());
  const bool root = p.uid == 0;
  if (root) {
    add(Finding::Level::info, "user",
        "running as root: the " + p.group + " group and the device rules are for lab users");
  } else if (!gr) {
    add(Finding::Level::warn, "user", "no group '" + p.group + "' on this machine");
    a.advice.push_back("install the palprig package (it creates the group), or: sudo addgroup --system " + p.group);
  } else if (has(p.login_groups, gr->gr_gid)) {
    add(Finding::Level::ok, "user", p.user + " is in the " + p.group + " group");
  } else if (has(p.member_of, gr->gr_gid)) {
    add(Finding::Level::warn, "user",
        p.user + " was added to the " + p.group + " group, but this login does not have it yet");
    a.advice.push_back("log out and in again (or reboot) so that the " + p.group + " group and its limits apply");
  } else {
    add(Finding::Level::warn, "user", p.user + " is not in the " + p.group + " group");
    a.advice.push_back("sudo adduser " + p.user + " " + p.group + ", then log out and in again");
  }

  std::error_code ec;
  if (fs::is_regular_file(p.limits_file, ec))
    add(Finding::Level::ok, "limits", p.limits_file.string() + " gives the group real-time priority and locked memory");
  else if (!root) {
    add(Finding::Level::warn, "limits", "no " + p.limits_file.string() + " (the palprig package installs it)");
    a.advice.push_back("install the palprig package, or copy packaging/palprig-limits.conf to " +
                       p.limits_file.string());
  }

  // Every comedi card and every pen tablet: may this user open it read-write?
  std::vector<std::pair<fs::path, std::string>> devices;  // node, what it is
  for (fs::directory_iterator it(p.dev_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("comedi", 0) == 0 && name.find('_') == std::string::npos)
      devices.push_back({it->path(), "comedi card"});
  }
  const bool udev = fs::is_directory(p.udev_data_dir, ec);
  for (fs::directory_iterator it(p.dev_dir / "input", ec), end; !ec && it != end; it.increment(ec)) {
    struct stat st {};
    if (it->path().filename().string().rfind("event", 0) != 0 || ::stat(it->path().c_str(), &st) != 0) continue;
    if (udev && udev_says_tablet(p.udev_data_dir, st)) devices.push_back({it->path(), "pen tablet"});
  }
  std::sort(devices.begin(), devices.end());
  std::vector<gid_t> groups = p.login_groups;
  for (const auto& [node, what] : devices) {
    struct stat st {};
    if (::stat(node.c_str(), &st) != 0) continue;
    if (may_read_write(p.uid, groups, st.st_uid, st.st_gid, st.st_mode)) {
      add(Finding::Level::ok, "devices", what + " " + node.string() + ": read-write for " + p.user);
    } else {
      add(Finding::Level::warn, "devices",
          what + " " + node.string() + " (group " + group_name(st.st_gid) + ", mode " +
              std::to_string((st.st_mode >> 6) & 7) + std::to_string((st.st_mode >> 3) & 7) +
              std::to_string(st.st_mode & 7) + "): " + p.user + " may not open it read-write");
      if (a.advice.empty() || a.advice.back().find("udev") == std::string::npos)
        a.advice.push_back("the palprig package's udev rules give the " + p.group +
                           " group the comedi cards and tablets: install it, be in the group, replug the device");
    }
  }
  if (devices.empty())
    add(Finding::Level::info, "devices",
        std::string("no comedi card") + (udev ? " and no pen tablet" : "; tablets not looked for (no udev database)") +
            " found (a Modbus rig needs neither)");
  return a;
}

}  // namespace palprig
