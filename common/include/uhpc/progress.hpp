#pragma once
// A progress indicator for long loops: count, percentage, rate and ETA. On a terminal it rewrites one
// line in place (at most 10 times a second); otherwise (a log file, CI, make -j) it prints plain lines,
// at most one per `plain_interval_s`, so logs stay readable. advance() is thread-safe and cheap (one
// atomic add; printing is attempted only by the thread that wins a try-lock).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <mutex>
#include <string>

namespace uhpc {

struct ProgressOptions {
  std::ostream* out = nullptr;   // nullptr: std::cerr
  int tty = -1;                  // -1: detect from stderr; 0: plain lines; 1: in-place line
  double plain_interval_s = 10;  // minimum time between plain lines
  double tty_interval_s = 0.1;   // minimum time between in-place updates
  std::string unit = "";         // what is counted ("steps", "cells"), shown with the rate
};

class Progress {
 public:
  Progress(std::string label, std::uint64_t total, ProgressOptions options = {});
  ~Progress();  // finishes if finish() was not called
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // `work`: the items' share of a total set with set_work_total (0 when no total is set).
  void advance(std::uint64_t n = 1, double work = 0.0);
  // Items that turn out to need no work (a resumed run's finished cells) leave the count, so the
  // rate and the ETA describe the work still to do.
  void skip(std::uint64_t n = 1, double work = 0.0);
  // Items of unequal cost (cells of four sizes, the largest 20x the smallest): with a total work the
  // percentage and the ETA follow the work done, not the count; the caller passes each item's expected
  // work to advance() and skip().
  void set_work_total(double work);
  void finish();  // prints the final line with the elapsed time (once)

  std::uint64_t done() const { return done_.load(std::memory_order_relaxed); }

  // "label: 120/400 (30.0%), 12.5 steps/s, ETA 22s" (total 0: no percentage and no ETA). With a work
  // total > 0: "label: 4/51 (28.0% of the work), ..., ETA" from the work's rate.
  static std::string format(const std::string& label, std::uint64_t done, std::uint64_t total, double elapsed_s,
                            const std::string& unit, double work_done = 0.0, double work_total = 0.0);

 private:
  void print(bool final);
  double elapsed() const;

  std::string label_;
  std::atomic<std::uint64_t> total_;
  ProgressOptions options_;
  bool tty_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<double> work_done_{0.0};
  std::atomic<double> work_total_{0.0};
  std::chrono::steady_clock::time_point start_;
  double last_print_s_ = -1e300;
  bool finished_ = false;
  std::mutex mutex_;
};

// 0.4 -> "0.4s", 75 -> "1m15s", 3725 -> "1h02m".
std::string format_duration(double seconds);

}  // namespace uhpc
