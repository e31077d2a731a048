#pragma once
// One owner of the rig at a time. A Rig is an opened backend; whatever drives it (the live loop,
// a study session, a calibration sweep or evaluation) first takes its RigLease and drives it
// only through that lease, and the lease goes back by scope: its destructor vents and disarms
// every channel before the next taker can have it. A second taker while a lease is out is
// refused with one line naming the holder (RigBusy), unless the holder took a yielding lease
// (the window's live loop, which runs whenever nothing else needs the rig): then the holder is
// asked to give way (release_requested(), read by its loop every tick), and the new taker waits
// for it.
//
// Across processes, a hardware rig (Modbus, comedi) is also locked on the machine while it is
// open (an flock on a file under /run/lock, released by the kernel when the process ends), so a
// second palprig cannot drive the same regulators; the in-process simulated rig is every
// process's own and is not locked.
//
// Taking and returning a lease lock a mutex and may wait: never on the real-time loop's
// thread. release_requested() is a lock-free read the loop makes every tick.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "formats/rig_file.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig {

// The rig is held by someone else: nothing was started, nothing moved.
class RigBusy : public Error {
 public:
  explicit RigBusy(const std::string& what) : Error(what) {}
};

enum class LeaseKind {
  exclusive,  // held until the holder is done
  yielding,   // the holder gives way when another taker asks (release_requested())
};

class RigLease;

class Rig {
 public:
  // A backend this Rig owns (closed when the Rig goes): make_rig makes it, open() opens it.
  Rig(std::unique_ptr<RigBackend> backend, std::string name, std::vector<std::string> device_lock_paths = {});
  // A backend opened and owned by the caller (tests, benchmarks); it must outlive the Rig.
  Rig(RigBackend& opened, std::string name);
  ~Rig();
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  // Takes the machine-wide locks of the device (RigBusy when another process has it), then opens
  // the backend (connected, vented; Error with one line when it cannot be reached). A Rig made
  // around a caller's opened backend is already open.
  void open();

  // The exclusive right to drive the rig. Throws RigBusy when another lease is out and does not
  // yield (or did not give way within `wait`), and refuses a yielding taker while another taker
  // waits (the waiter comes first).
  RigLease lease(std::string holder, LeaseKind kind = LeaseKind::exclusive,
                 std::chrono::milliseconds wait = std::chrono::seconds(5));

  // A lease is out, or a taker is waiting for a yielding holder to give way (promised to it).
  bool leased() const;
  std::string holder() const;  // "" when free
  // Asks a yielding holder to give way (its loop ends vented at its next tick and gives the
  // lease back from its own thread). Any thread, lock-free; nothing when none is out.
  void request_release() noexcept { release_requested_.store(true, std::memory_order_release); }
  const std::string& name() const noexcept { return name_; }
  // Reading what the rig is (describe, capabilities, state, linked) is allowed without a lease;
  // moving air is not: write through a lease.
  const RigBackend& backend() const noexcept { return *backend_; }

 private:
  friend class RigLease;
  void give_back(std::uint64_t ticket) noexcept;

  std::unique_ptr<RigBackend> owned_;
  RigBackend* backend_;
  std::string name_;
  mutable std::mutex mutex_;
  std::condition_variable returned_;
  std::string holder_;        // guarded by mutex_
  std::uint64_t ticket_ = 0;  // the lease out now (0: none); guarded by mutex_
  int waiting_ = 0;           // takers waiting for a yielding holder to give way; guarded by mutex_
  LeaseKind kind_ = LeaseKind::exclusive;
  std::atomic<bool> release_requested_{false};
  class DeviceLock;
  std::vector<std::string> device_lock_paths_;
  std::vector<std::unique_ptr<DeviceLock>> device_locks_;
};

// Move-only; a moved-from lease holds nothing.
class RigLease {
 public:
  RigLease(RigLease&& other) noexcept;
  RigLease& operator=(RigLease&& other) noexcept;
  RigLease(const RigLease&) = delete;
  RigLease& operator=(const RigLease&) = delete;
  ~RigLease();  // vents, disarms and gives the rig back

  RigBackend& backend() noexcept { return *rig_->backend_; }
  const RigBackend& backend() const noexcept { return *rig_->backend_; }
  Rig& rig() noexcept { return *rig_; }
  // Another taker asked this (yielding) lease to give way: its loop ends and drops the lease.
  // Any thread, lock-free. The holder may also ask its own lease (the window closing).
  bool release_requested() const noexcept { return rig_ && rig_->release_requested_.load(std::memory_order_acquire); }
  void request_release() noexcept {
    if (rig_) rig_->release_requested_.store(true, std::memory_order_release);
  }
  // Give the rig back now (as the destructor does).
  void release() noexcept;

 private:
  friend class Rig;
  RigLease(Rig& rig, std::uint64_t ticket) : rig_(&rig), ticket_(ticket) {}
  Rig* rig_ = nullptr;
  std::uint64_t ticket_ = 0;
};

// The rig file's backend (make_backend) in a Rig, not yet opened: a command may describe it (its
// capabilities, its endpoint) before anything connects. Throws InputError for a bad backend section.
std::unique_ptr<Rig> make_rig(const RigConfig& config);
// make_rig, then open(): the rig a run, a session or the window drives. Throws InputError for a
// bad backend section, RigBusy when another process has the device, Error when it cannot be reached.
std::unique_ptr<Rig> open_rig(const RigConfig& config);

// The machine-wide locks of a hardware rig: one file per device (each Modbus link, the comedi
// board) under /run/lock (PALPRIG_LOCK_DIR points elsewhere); none for the simulated rig.
std::vector<std::string> device_lock_paths(const RigConfig& config);

}  // namespace palprig
