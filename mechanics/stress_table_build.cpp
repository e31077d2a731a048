#include "mechanics/stress_table_build.hpp"

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace palprig::mechanics {

namespace {

using Clock = std::chrono::steady_clock;

struct Cell {
  bool healthy = false;
  double cover_mm = 0, diameter_mm = 0, contrast = 1, offset_mm = 0;
};

std::string describe(const Cell& c) {
  if (c.healthy) return "the healthy block";
  std::ostringstream o;
  o << "a nodule " << c.diameter_mm << " mm across, " << c.cover_mm << " mm under the surface, " << c.contrast
    << " times stiffer, " << c.offset_mm << " mm to the side";
  return o.str();
}

// One record on a worker's pipe: cell index, status (0: values follow; 1: an error text follows),
// the count of doubles (or of the text's bytes), the payload.
struct RecordHeader {
  std::uint64_t cell;
  std::uint32_t status;
  std::uint32_t count;
};

bool write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= std::size_t(n);
  }
  return true;
}

using CellSolver = std::function<std::vector<double>(std::size_t)>;
using CellDone = std::function<void(std::size_t done)>;

// Solve every cell in `workers` forked processes (cell i in worker i % workers); results by cell.
std::vector<std::vector<double>> solve_in_workers(std::size_t cells, int workers, const CellSolver& solve,
                                                  const CellDone& done) {
  std::vector<std::vector<double>> results(cells);
  if (workers <= 1 || cells < 2) {
    for (std::size_t i = 0; i < cells; ++i) {
      results[i] = solve(i);
      done(i + 1);
    }
    return results;
  }
  workers = int(std::min<std::size_t>(std::size_t(workers), cells));
  std::vector<pid_t> pids;
  std::vector<int> fds;
  for (int w = 0; w < workers; ++w) {
    int p[2];
    if (::pipe(p) != 0) throw Error(std::string("finite-element table: cannot make a pipe: ") + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) throw Error(std::string("finite-element table: cannot start a worker: ") + std::strerror(errno));
    if (pid == 0) {  // the worker: solve its cells, send each, leave without running the parent's exit handlers
      ::close(p[0]);
      for (int fd : fds) ::close(fd);
      int status = 0;
      for (std::size_t i = std::size_t(w); i < cells; i += std::size_t(workers)) {
        RecordHeader h{i, 0, 0};
        try {
          const std::vector<double> v = solve(i);
          h.count = std::uint32_t(v.size());
          if (!write_all(p[1], &h, sizeof h) || !write_all(p[1], v.data(), v.size() * sizeof(double))) status = 1;
        } catch (const std::exception& e) {
          const std::string why = e.what();
          h.status = 1;
          h.count = std::uint32_t(why.size());
          (void)write_all(p[1], &h, sizeof h);
          (void)write_all(p[1], why.data(), why.size());
          status = 1;
          break;
        }
      }
      ::close(p[1]);
      ::_exit(status);
    }
    ::close(p[1]);
    pids.push_back(pid);
    fds.push_back(p[0]);
  }
  std::vector<std::string> buffers(fds.size());
  std::vector<bool> open(fds.size(), true);
  std::size_t received = 0;
  std::string failure;
  while (std::any_of(open.begin(), open.end(), [](bool b) { return b; })) {
    std::vector<pollfd> polled;
    std::vector<std::size_t> which;
    for (std::size_t k = 0; k < fds.size(); ++k)
      if (open[k]) {
        polled.push_back({fds[k], POLLIN, 0});
        which.push_back(k);
      }
    if (::poll(polled.data(), polled.size(), -1) < 0) {
      if (errno == EINTR) continue;
      failure = std::string("poll: ") + std::strerror(errno);
      break;
    }
    for (std::size_t j = 0; j < polled.size(); ++j) {
      if (!(polled[j].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const std::size_t k = which[j];
      char chunk[65536];
      const ssize_t n = ::read(fds[k], chunk, sizeof chunk);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        open[k] = false;
        continue;
      }
      buffers[k].append(chunk, std::size_t(n));
      for (;;) {  // every whole record in the buffer
        std::string& b = buffers[k];
        if (b.size() < sizeof(RecordHeader)) break;
        RecordHeader h;
        std::memcpy(&h, b.data(), sizeof h);
        const std::size_t payload = h.status == 0 ? h.count * sizeof(double) : h.count;
        if (b.size() < sizeof h + payload) break;
        if (h.status != 0 || h.cell >= cells) {
          if (failure.empty()) failure = b.substr(sizeof h, payload);
        } else {
          std::vector<double> v(h.count);
          std::memcpy(v.data(), b.data() + sizeof h, payload);
          results[h.cell] = std::move(v);
          done(++received);
        }
        b.erase(0, sizeof h + payload);
      }
    }
  }
  for (int fd : fds) ::close(fd);
  bool worker_failed = false;
  for (pid_t pid : pids) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    worker_failed = worker_failed || !WIFEXITED(status) || WEXITSTATUS(status) != 0;
  }
  if (!failure.empty()) throw Error(failure);
  if (worker_failed || received != cells)
    throw Error("finite-element table: a worker stopped before its solves were done (" + std::to_string(received) +
                " of " + std::to_string(cells) + " received)");
  return results;
}

}  // namespace

TissueBlock table_block(const TissueBlock& tissue, const FeTableAxes& axes) {
  TissueBlock block = tissue;
  block.inclusions.clear();
  const double reach = axes.offset_mm.back() + axes.diameter_mm.back() / 2 + 8.0;
  block.width_mm = std::max(block.width_mm, 2 * reach);
  return block;
}

TableBuild build_stress_table(const FingertipBody& finger, const TissueBlock& tissue, const FeTableAxes& axes,
                              const TableBuildOptions& options, const ProgressFn& progress) {
  const auto t0 = Clock::now();
  const TissueBlock block = table_block(tissue, axes);
  std::vector<Cell> cells{{true, 0, 0, 1, 0}};
  for (double c : axes.cover_mm)
    for (double d : axes.diameter_mm)
      for (double k : axes.contrast)
        for (double o : axes.offset_mm) cells.push_back({false, c, d, k, o});
  IndentationOptions io;
  io.solve = options.solve;
  io.depths_mm = axes.indentation_mm;
  auto solve = [&](std::size_t i) {
    const Cell& cell = cells[i];
    TissueBlock b = block;
    if (!cell.healthy) {
      BlockInclusion inc;
      inc.name = "nodule";
      inc.x_mm = cell.offset_mm;
      inc.diameter_mm = cell.diameter_mm;
      inc.centre_depth_mm = cell.cover_mm + cell.diameter_mm / 2;
      inc.law = block.tissue.scaled(cell.contrast);
      b.inclusions.push_back(inc);
    }
    try {
      const ContactRun run = run_indentation(finger, b, io);
      std::vector<double> peaks;
      for (const ContactStep& s : run.steps) peaks.push_back(s.peak_kPa);
      return peaks;
    } catch (const std::exception& e) {
      throw Error("finite-element table: " + describe(cell) + ": " + e.what());
    }
  };
  auto done = [&](std::size_t n) {
    if (!progress) return;
    StepProgress p;
    p.step = int(n);
    p.steps = int(cells.size());
    p.what = "solve " + std::to_string(n) + " of " + std::to_string(cells.size());
    p.elapsed_s = std::chrono::duration<double>(Clock::now() - t0).count();
    p.remaining_s = p.elapsed_s / double(n) * double(cells.size() - n);
    progress(p);
  };
  const auto results = solve_in_workers(cells.size(), options.workers, solve, done);
  const std::size_t depths = axes.indentation_mm.size();
  for (std::size_t i = 0; i < results.size(); ++i)
    if (results[i].size() != depths)
      throw Error("finite-element table: " + describe(cells[i]) + " gave a short result");
  std::vector<double> peak(axes.values());
  // The table's order: indentation slowest, then cover, diameter, contrast, offset (cells' order).
  for (std::size_t i = 0; i < depths; ++i)
    for (std::size_t c = 1; c < cells.size(); ++c) peak[i * (cells.size() - 1) + (c - 1)] = results[c][i];
  TableBuild out{FeStressTable(axes, std::move(peak), results[0]), cells.size(), 0, std::max(1, options.workers),
                 block.width_mm};
  out.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

}  // namespace palprig::mechanics
