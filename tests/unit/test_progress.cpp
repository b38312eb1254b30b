// Progress reporting: the line format, durations, plain (non-terminal) output and thread safety.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <thread>
#include <vector>

#include "uhpc/progress.hpp"

namespace {

// Plain (non-terminal) output into `out`, a line at most every `interval_s` seconds.
uhpc::ProgressOptions plain_options(std::ostringstream& out, double interval_s) {
  uhpc::ProgressOptions o;
  o.out = &out;
  o.tty = 0;
  o.plain_interval_s = interval_s;
  return o;
}

TEST(Progress, FormatsCountPercentageRateAndEta) {
  EXPECT_EQ(uhpc::Progress::format("cells", 25, 100, 5.0, "cells"), "cells: 25/100 (25.0%), 5 cells/s, ETA 15s");
  EXPECT_EQ(uhpc::Progress::format("run", 3, 0, 2.0, ""), "run: 3, 1.5/s");
  EXPECT_EQ(uhpc::Progress::format("run", 10, 10, 2.0, ""), "run: 10/10 (100.0%), 5/s");
}

TEST(Progress, FormatsDurations) {
  EXPECT_EQ(uhpc::format_duration(0.42), "0.4s");
  EXPECT_EQ(uhpc::format_duration(42), "42s");
  EXPECT_EQ(uhpc::format_duration(75), "1m15s");
  EXPECT_EQ(uhpc::format_duration(3725), "1h02m");
  EXPECT_EQ(uhpc::format_duration(-1), "?");
}

TEST(Progress, PlainOutputIsWholeLinesWithAFinalSummary) {
  std::ostringstream out;
  {
    uhpc::Progress p("steps", 4, plain_options(out, 0.0));  // a line at every advance
    for (int i = 0; i < 4; ++i) p.advance();
    p.finish();
    p.finish();  // idempotent
  }
  const std::string text = out.str();
  EXPECT_EQ(text.find('\r'), std::string::npos);
  EXPECT_NE(text.find("steps: 1/4 (25.0%)"), std::string::npos);
  EXPECT_NE(text.find("steps: 4/4 (100.0%)"), std::string::npos);
  EXPECT_NE(text.find("done in"), std::string::npos);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 5);
}

TEST(Progress, PlainOutputIsThrottled) {
  std::ostringstream out;
  uhpc::Progress p("steps", 1000, plain_options(out, 3600.0));
  for (int i = 0; i < 1000; ++i) p.advance();
  p.finish();
  // The first advance prints (nothing printed before), then nothing until finish().
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
}

TEST(Progress, SkippedItemsLeaveTheCountAndTheEta) {
  std::ostringstream out;
  uhpc::Progress p("cells", 10, plain_options(out, 0.0));
  p.skip(6);  // finished in an earlier run
  p.advance();
  EXPECT_NE(out.str().find("cells: 1/4 (25.0%)"), std::string::npos);
  p.skip();
  p.advance(2);
  p.finish();
  EXPECT_NE(out.str().find("cells: 3/3 (100.0%)"), std::string::npos) << out.str();
}

TEST(Progress, WorkWeightsThePercentageAndTheEta) {
  // 1 of 4 items in 10 s, but only 0.1 of the work: 0.9 left at 0.01 per s is 90 s (by count: 30 s).
  EXPECT_EQ(uhpc::Progress::format("cells", 1, 4, 10.0, "cells", 0.1, 1.0),
            "cells: 1/4 (10.0% of the work), 0.1 cells/s, ETA 1m30s");
  std::ostringstream out;
  uhpc::Progress p("cells", 10, plain_options(out, 0.0));
  p.set_work_total(100.0);
  p.skip(6, 60.0);     // reloaded: 4 cells and 40 of work left
  p.advance(1, 30.0);  // the largest first
  EXPECT_NE(out.str().find("cells: 1/4 (75.0% of the work)"), std::string::npos) << out.str();
  p.advance(3, 10.0);
  p.finish();
  EXPECT_NE(out.str().find("cells: 4/4 (100.0% of the work)"), std::string::npos) << out.str();
}

TEST(Progress, CountsEveryAdvanceFromManyThreads) {
  std::ostringstream out;
  uhpc::ProgressOptions o;
  o.out = &out;
  o.tty = 1;
  uhpc::Progress p("work", 40000, o);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 10000; ++i) p.advance();
    });
  for (auto& t : threads) t.join();
  p.finish();
  EXPECT_EQ(p.done(), 40000u);
  EXPECT_NE(out.str().find("work: 40000/40000"), std::string::npos);
}

}  // namespace
