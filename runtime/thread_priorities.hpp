#pragma once
// The SCHED_FIFO priorities of palprig's threads, in one place so their order is stated.
// The loop is highest: it owns the deadlines. The Modbus bus thread sits below it (it only
// carries the newest setpoint out and the newest monitor in, through wait-free exchanges, and
// a slow bus must never delay a tick). The pen tablet reader sits below the bus: a pen event
// that waits a little is still read by the next tick, while a late bus cycle holds a whole
// pressure update. The telemetry writer and everything else run at normal priority. All stay
// below 99, which the kernel's own threads (watchdogs, migration) need.
//   loop              80   palprig run --priority, RealtimeOptions::fifo_priority
//   Modbus bus thread 70   rig file modbus.io_thread_fifo_priority (0: normal scheduling)
//   tablet reader     60   rig file tablet.reader_fifo_priority   (0: normal scheduling)
//   tracker reader    60   tracking file reader_fifo_priority     (0: normal scheduling); like the
//                          tablet's: a pose that waits a little is read by the next tick
//   telemetry writer   0   normal scheduling
namespace palprig {

inline constexpr int kLoopFifoPriority = 80;
inline constexpr int kBusThreadFifoPriority = 70;
inline constexpr int kTabletReaderFifoPriority = 60;
inline constexpr int kTrackerReaderFifoPriority = 60;

}  // namespace palprig
