// rt-check's user part: the palprig group (absent, not joined, joined but not in this login,
// in it), the limits.d file and the devices, on fixture /dev trees and a synthetic user (the
// suite runs as root, for whom every device is open, so the user is never this process's).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <algorithm>
#include <fstream>

#include "diagnostics/rig_user_access.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

constexpr uid_t kLabUser = 4242;
constexpr gid_t kRootGroup = 0;  // a group every machine has ("root"); it stands for palprig here

void put(const std::filesystem::path& p, const std::string& text, mode_t mode) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
  ASSERT_EQ(::chmod(p.c_str(), mode), 0);
}

RigUserProbe probe(const TempDir& dir) {
  RigUserProbe p;
  p.group = "root";
  p.limits_file = dir.path() / "limits.d" / "palprig.conf";
  p.dev_dir = dir.path() / "dev";
  p.udev_data_dir = dir.path() / "udev";
  p.uid = kLabUser;
  p.user = "lab";
  std::filesystem::create_directories(p.dev_dir);
  std::filesystem::create_directories(p.udev_data_dir);
  return p;
}

const Finding* topic(const RigUserAccess& a, const std::string& t) {
  const auto it = std::find_if(a.findings.begin(), a.findings.end(), [&](const Finding& f) { return f.topic == t; });
  return it == a.findings.end() ? nullptr : &*it;
}

bool advises(const RigUserAccess& a, const std::string& words) {
  return std::any_of(a.advice.begin(), a.advice.end(),
                     [&](const std::string& s) { return s.find(words) != std::string::npos; });
}

}  // namespace

TEST(RigUserAccess, PermissionBitsForOwnerGroupAndOthers) {
  EXPECT_TRUE(may_read_write(0, {}, 1, 1, 0));                     // root
  EXPECT_TRUE(may_read_write(kLabUser, {}, kLabUser, 1, 0600));    // owner
  EXPECT_FALSE(may_read_write(kLabUser, {1}, kLabUser, 1, 0460));  // owner bits decide for the owner
  EXPECT_TRUE(may_read_write(kLabUser, {7}, 1, 7, 0660));          // group
  EXPECT_FALSE(may_read_write(kLabUser, {7}, 1, 7, 0640));         // group may only read
  EXPECT_FALSE(may_read_write(kLabUser, {8}, 1, 7, 0660));         // another group
  EXPECT_TRUE(may_read_write(kLabUser, {}, 1, 7, 0666));           // everyone
}

TEST(RigUserAccess, GroupMissingNotJoinedNotYetInThisLoginAndIn) {
  TempDir dir;
  RigUserProbe p = probe(dir);
  p.group = "palprig-no-such-group-here";
  RigUserAccess a = check_rig_user_access(p);
  ASSERT_NE(topic(a, "user"), nullptr);
  EXPECT_EQ(topic(a, "user")->level, Finding::Level::warn);
  EXPECT_NE(topic(a, "user")->text.find("no group"), std::string::npos);
  EXPECT_TRUE(advises(a, "addgroup --system"));

  p.group = "root";
  a = check_rig_user_access(p);
  EXPECT_NE(topic(a, "user")->text.find("lab is not in the root group"), std::string::npos);
  EXPECT_TRUE(advises(a, "sudo adduser lab root"));

  p.member_of = {kRootGroup};  // in /etc/group, but the login predates it
  a = check_rig_user_access(p);
  EXPECT_EQ(topic(a, "user")->level, Finding::Level::warn);
  EXPECT_NE(topic(a, "user")->text.find("this login does not have it yet"), std::string::npos);
  EXPECT_TRUE(advises(a, "log out and in"));

  p.login_groups = {kRootGroup};
  a = check_rig_user_access(p);
  EXPECT_EQ(topic(a, "user")->level, Finding::Level::ok);
  EXPECT_FALSE(advises(a, "adduser"));
}

TEST(RigUserAccess, LimitsFileSaidWhenMissing) {
  TempDir dir;
  RigUserProbe p = probe(dir);
  RigUserAccess a = check_rig_user_access(p);
  ASSERT_NE(topic(a, "limits"), nullptr);
  EXPECT_EQ(topic(a, "limits")->level, Finding::Level::warn);
  put(p.limits_file, "@palprig - rtprio 90\n", 0644);
  a = check_rig_user_access(p);
  EXPECT_EQ(topic(a, "limits")->level, Finding::Level::ok);
}

TEST(RigUserAccess, ComediCardAndTabletOpenOnlyThroughTheGroup) {
  TempDir dir;
  RigUserProbe p = probe(dir);
  put(p.dev_dir / "comedi0", "", 0660);        // root:root 0660, as the udev rule makes it for palprig
  put(p.dev_dir / "comedi0_subd1", "", 0660);  // a subdevice: not a card of its own
  put(p.dev_dir / "input" / "event3", "", 0660);
  struct stat st {};
  ASSERT_EQ(::stat((p.dev_dir / "input" / "event3").c_str(), &st), 0);
  put(p.udev_data_dir / ("c" + std::to_string(major(st.st_rdev)) + ":" + std::to_string(minor(st.st_rdev))),
      "E:ID_INPUT=1\nE:ID_INPUT_TABLET=1\n", 0644);

  RigUserAccess a = check_rig_user_access(p);  // the lab user, not in the group
  std::vector<const Finding*> devices;
  for (const Finding& f : a.findings)
    if (f.topic == "devices") devices.push_back(&f);
  ASSERT_EQ(devices.size(), 2u);
  EXPECT_EQ(devices[0]->level, Finding::Level::warn);
  EXPECT_NE(devices[0]->text.find("comedi card"), std::string::npos);
  EXPECT_NE(devices[0]->text.find("mode 660"), std::string::npos);
  EXPECT_EQ(devices[1]->level, Finding::Level::warn);
  EXPECT_NE(devices[1]->text.find("pen tablet"), std::string::npos);
  EXPECT_TRUE(advises(a, "udev rules"));

  p.login_groups = {st.st_gid};  // in the devices' group now (the group the fixture files got)
  a = check_rig_user_access(p);
  for (const Finding& f : a.findings)
    if (f.topic == "devices") EXPECT_EQ(f.level, Finding::Level::ok) << f.text;
  EXPECT_FALSE(advises(a, "udev rules"));
}

TEST(RigUserAccess, NoDeviceIsNotAProblemAndAKeyboardIsNoTablet) {
  TempDir dir;
  const RigUserProbe p = probe(dir);
  put(p.dev_dir / "input" / "event0", "", 0600);  // a keyboard udev knows as one: not looked at
  struct stat st {};
  ASSERT_EQ(::stat((p.dev_dir / "input" / "event0").c_str(), &st), 0);
  put(p.udev_data_dir / ("c" + std::to_string(major(st.st_rdev)) + ":" + std::to_string(minor(st.st_rdev))),
      "E:ID_INPUT=1\nE:ID_INPUT_KEYBOARD=1\n", 0644);
  const RigUserAccess a = check_rig_user_access(p);
  ASSERT_NE(topic(a, "devices"), nullptr);
  EXPECT_EQ(topic(a, "devices")->level, Finding::Level::info);
  EXPECT_NE(topic(a, "devices")->text.find("a Modbus rig needs neither"), std::string::npos);
}
