#include "controller/rig_lease.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "controller/backend_factory.hpp"

namespace palprig {

// The machine-wide lock of a hardware rig's device: an flock on a file named after the device,
// held while the Rig is open and dropped by the kernel when the process ends (a crash leaves no
// stale lock). The file holds the holder's pid and command line for the refusal's message.
class Rig::DeviceLock {
 public:
  DeviceLock(const std::string& path, const std::string& device) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd_ < 0) throw Error(path + ": cannot open the lock file of " + device + ": " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int why = errno;
      const std::string holder = read_holder();
      ::close(fd_);
      if (why == EWOULDBLOCK)
        throw RigBusy(device + " is in use by another palprig" + (holder.empty() ? "" : " (" + holder + ")") +
                      ": one program drives a rig at a time; stop it first (lock " + path + ")");
      throw Error(path + ": cannot lock " + device + ": " + std::strerror(why));
    }
    // Who holds it, for the next taker's message; a lock whose note cannot be written still locks.
    std::ostringstream note;
    note << "pid " << ::getpid() << ": " << own_command_line();
    const std::string text = note.str();
    if (::ftruncate(fd_, 0) == 0) {
      const ssize_t n = ::pwrite(fd_, text.data(), text.size(), 0);
      (void)n;
    }
  }
  ~DeviceLock() {
    if (::ftruncate(fd_, 0) != 0) {
      // Nothing to do: the lock itself goes with the descriptor.
    }
    ::close(fd_);
  }
  DeviceLock(const DeviceLock&) = delete;
  DeviceLock& operator=(const DeviceLock&) = delete;

 private:
  std::string read_holder() const {
    char buf[256] = {0};
    const ssize_t n = ::pread(fd_, buf, sizeof buf - 1, 0);
    return n > 0 ? std::string(buf, std::size_t(n)) : std::string();
  }
  static std::string own_command_line() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (char& c : raw)
      if (c == '\0') c = ' ';
    while (!raw.empty() && raw.back() == ' ') raw.pop_back();
    return raw.size() > 160 ? raw.substr(0, 160) + "..." : raw;
  }

  std::string path_;
  int fd_ = -1;
};

Rig::Rig(std::unique_ptr<RigBackend> backend, std::string name, std::vector<std::string> device_lock_paths)
    : owned_(std::move(backend)),
      backend_(owned_.get()),
      name_(std::move(name)),
      device_lock_paths_(std::move(device_lock_paths)) {}

void Rig::open() {
  if (!owned_) return;  // the caller's backend, opened by the caller
  std::vector<std::unique_ptr<DeviceLock>> locks;
  for (const std::string& path : device_lock_paths_) locks.push_back(std::make_unique<DeviceLock>(path, name_));
  owned_->open();  // throws with one line when the device cannot be reached; the locks go with it
  device_locks_ = std::move(locks);
}

Rig::Rig(RigBackend& opened, std::string name) : backend_(&opened), name_(std::move(name)) {}

Rig::~Rig() {
  if (owned_) {
    owned_->vent();
    owned_->close();
  }
}

RigLease Rig::lease(std::string holder, LeaseKind kind, std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  // A taker already waiting for a yielding holder to give way comes first: the window's live
  // loop, restarting on its own timer in the moment between the old lease going back and the
  // waiter waking, would otherwise take the rig again with nobody left to ask it to give way,
  // and the waiter would time out (seen under load in CI: a study session refused after 5 s).
  if (kind == LeaseKind::yielding && waiting_ > 0)
    throw RigBusy(name_ + " is wanted by a taker waiting for it: " + holder + " cannot take it now");
  if (ticket_ != 0) {
    if (kind_ != LeaseKind::yielding)
      throw RigBusy(name_ + " is held by " + holder_ + ": " + holder + " cannot take it until that ends");
    ++waiting_;
    const auto deadline = std::chrono::steady_clock::now() + wait;
    while (ticket_ != 0) {
      // Another waiter got it first and does not yield: refused as any second taker is.
      if (kind_ != LeaseKind::yielding) {
        --waiting_;
        throw RigBusy(name_ + " is held by " + holder_ + ": " + holder + " cannot take it until that ends");
      }
      // The window's live loop runs whenever nothing else needs the rig: ask it to give way
      // (again, each time round: the holder may have changed while this taker slept).
      release_requested_.store(true, std::memory_order_release);
      if (returned_.wait_until(lock, deadline) == std::cv_status::timeout && ticket_ != 0) {
        --waiting_;
        throw RigBusy(name_ + " is held by " + holder_ + ", which did not give it up within " +
                      std::to_string(wait.count()) + " ms: " + holder + " cannot take it");
      }
    }
    --waiting_;
  }
  static std::atomic<std::uint64_t> next_ticket{1};
  ticket_ = next_ticket.fetch_add(1);
  holder_ = std::move(holder);
  kind_ = kind;
  release_requested_.store(false, std::memory_order_release);
  return RigLease(*this, ticket_);
}

bool Rig::leased() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ticket_ != 0 || waiting_ > 0;
}

std::string Rig::holder() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return holder_;
}

void Rig::give_back(std::uint64_t ticket) noexcept {
  // Every channel to 0 kPa before anyone else may drive it.
  if (backend_->armed())
    backend_->disarm();
  else
    backend_->vent();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (ticket_ != ticket) return;
    ticket_ = 0;
    holder_.clear();
  }
  returned_.notify_all();
}

RigLease::RigLease(RigLease&& other) noexcept : rig_(other.rig_), ticket_(other.ticket_) {
  other.rig_ = nullptr;
  other.ticket_ = 0;
}

RigLease& RigLease::operator=(RigLease&& other) noexcept {
  if (this != &other) {
    release();
    rig_ = other.rig_;
    ticket_ = other.ticket_;
    other.rig_ = nullptr;
    other.ticket_ = 0;
  }
  return *this;
}

RigLease::~RigLease() { release(); }

void RigLease::release() noexcept {
  if (!rig_) return;
  rig_->give_back(ticket_);
  rig_ = nullptr;
  ticket_ = 0;
}

namespace {

std::string lock_dir() {
  if (const char* dir = std::getenv("PALPRIG_LOCK_DIR"); dir && *dir) return dir;
  if (::access("/run/lock", W_OK) == 0) return "/run/lock";
  return "/tmp";
}

// A device as a file name: "modbus-tcp-10.0.0.5-502", "modbus-rtu--dev-ttyUSB0", "comedi--dev-comedi0".
std::string file_key(std::string key) {
  for (char& c : key)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.')) c = '-';
  return key;
}

std::vector<std::string> device_keys(const RigConfig& config) {
  std::vector<std::string> keys;
  if (config.backend == "modbus" && config.modbus)
    for (const ModbusLinkConfig& link : config.modbus->links)
      keys.push_back(file_key(link.rtu ? "modbus-rtu-" + link.device
                                       : "modbus-tcp-" + link.host + "-" + std::to_string(link.port)));
  if (config.backend == "comedi" && config.comedi) keys.push_back(file_key("comedi-" + config.comedi->device));
  return keys;
}

std::string device_text(const RigConfig& config) {
  return "rig " + (config.id.empty() ? config.source : config.id) + " (" + config.backend + ")";
}

}  // namespace

std::vector<std::string> device_lock_paths(const RigConfig& config) {
  std::vector<std::string> paths;
  for (const std::string& key : device_keys(config)) paths.push_back(lock_dir() + "/palprig-" + key + ".lock");
  return paths;
}

std::unique_ptr<Rig> make_rig(const RigConfig& config) {
  return std::make_unique<Rig>(make_backend(config), device_text(config), device_lock_paths(config));
}

std::unique_ptr<Rig> open_rig(const RigConfig& config) {
  std::unique_ptr<Rig> rig = make_rig(config);
  rig->open();
  return rig;
}

}  // namespace palprig
