#include "uhpc/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <iostream>

#include <fmt/format.h>

namespace uhpc {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 10) return fmt::format("{:.1f}s", seconds);
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 3600) return s < 60 ? fmt::format("{}s", s) : fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}h{:02}m", s / 3600, (s % 3600) / 60);
}

namespace {

void atomic_add(std::atomic<double>& a, double x) {
  double old = a.load(std::memory_order_relaxed);
  while (!a.compare_exchange_weak(old, old + x, std::memory_order_relaxed)) {
  }
}

}  // namespace

std::string Progress::format(const std::string& label, std::uint64_t done, std::uint64_t total, double elapsed_s,
                             const std::string& unit, double work_done, double work_total) {
  const double rate = elapsed_s > 0 ? static_cast<double>(done) / elapsed_s : 0.0;
  const std::string per = unit.empty() ? "/s" : " " + unit + "/s";
  const bool by_work = total > 0 && work_total > 0;
  std::string line;
  if (by_work)
    line = fmt::format("{}: {}/{} ({:.1f}% of the work)", label, done, total, 100.0 * work_done / work_total);
  else if (total > 0)
    line = fmt::format("{}: {}/{} ({:.1f}%)", label, done, total, 100.0 * done / total);
  else
    line = fmt::format("{}: {}", label, done);
  line += fmt::format(", {:.3g}{}", rate, per);
  if (by_work) {
    if (done < total && work_done > 0 && elapsed_s > 0)
      line += ", ETA " + format_duration(elapsed_s * std::max(0.0, work_total - work_done) / work_done);
  } else if (total > 0 && done < total && rate > 0) {
    line += ", ETA " + format_duration((total - done) / rate);
  }
  return line;
}

Progress::Progress(std::string label, std::uint64_t total, ProgressOptions options)
    : label_(std::move(label)), total_(total), options_(std::move(options)), start_(std::chrono::steady_clock::now()) {
  if (!options_.out) options_.out = &std::cerr;
  tty_ = options_.tty < 0 ? isatty(fileno(stderr)) != 0 : options_.tty == 1;
}

Progress::~Progress() {
  if (!finished_) finish();
}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::advance(std::uint64_t n, double work) {
  if (work != 0.0) atomic_add(work_done_, work);
  done_.fetch_add(n, std::memory_order_relaxed);
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || finished_) return;  // another thread is printing: skip, never wait
  const double interval = tty_ ? options_.tty_interval_s : options_.plain_interval_s;
  if (elapsed() - last_print_s_ >= interval) print(false);
}

void Progress::set_work_total(double work) { work_total_.store(work, std::memory_order_relaxed); }

void Progress::skip(std::uint64_t n, double work) {
  if (work != 0.0) atomic_add(work_total_, -work);
  std::uint64_t total = total_.load(std::memory_order_relaxed);
  while (!total_.compare_exchange_weak(total, total - std::min(n, total), std::memory_order_relaxed)) {
  }
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  print(true);
  finished_ = true;
}

void Progress::print(bool final) {
  const double t = elapsed();
  last_print_s_ = t;
  std::string line = format(label_, done(), total_.load(std::memory_order_relaxed), t, options_.unit,
                            work_done_.load(std::memory_order_relaxed), work_total_.load(std::memory_order_relaxed));
  if (final) line += ", done in " + format_duration(t);
  std::ostream& out = *options_.out;
  if (tty_) {
    out << "\r\033[K" << line;  // carriage return and clear-to-end-of-line
    if (final) out << '\n';
  } else {
    out << line << '\n';
  }
  out.flush();
}

}  // namespace uhpc
