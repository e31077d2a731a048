#pragma once
// A full disk for writers' tests: a 64 KiB tmpfs mounted on a folder and filled to the last
// block, so the next write fails with ENOSPC as on a real full disk. Mounting needs root (CI
// runs the tests as root); where it is refused, reason() says why and the test skips with it.
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace palprig::test_support {

class FullFilesystem {
 public:
  explicit FullFilesystem(const std::filesystem::path& folder) : folder_(folder) {
    std::filesystem::create_directories(folder_);
    if (::geteuid() != 0) {
      reason_ = "mounting a small tmpfs needs root";
      return;
    }
    if (::mount("tmpfs", folder_.c_str(), "tmpfs", 0, "size=64k,mode=0777") != 0) {
      reason_ = std::string("mount -t tmpfs refused: ") + std::strerror(errno);
      return;
    }
    mounted_ = true;
    // Fill it: write until the file system says no.
    std::ofstream filler(folder_ / "filler", std::ios::binary);
    const std::vector<char> block(4096, 'x');
    while (filler.write(block.data(), static_cast<std::streamsize>(block.size())) && filler.flush()) {}
  }
  ~FullFilesystem() {
    if (mounted_) ::umount2(folder_.c_str(), MNT_DETACH);
  }
  FullFilesystem(const FullFilesystem&) = delete;
  FullFilesystem& operator=(const FullFilesystem&) = delete;

  bool mounted() const { return mounted_; }
  const std::string& reason() const { return reason_; }
  const std::filesystem::path& folder() const { return folder_; }
  // What is on it besides the filler (a writer that failed must have left nothing).
  std::set<std::string> left_behind() const {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::recursive_directory_iterator(folder_)) {
      if (e.path().filename() != "filler") names.insert(std::filesystem::relative(e.path(), folder_).string());
    }
    return names;
  }

 private:
  std::filesystem::path folder_;
  bool mounted_ = false;
  std::string reason_;
};

}  // namespace palprig::test_support
