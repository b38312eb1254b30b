// uhpc-compare-json EXPECTED.json ACTUAL.json
//
// Compares a program's JSON result with a regression case's expectations:
//   {"checks": [{"pointer": "/lengths/0/peak_stress_Pa", "expected": 1.1119e7, "rel_tol": 1e-9,
//                "why": "stored result"}, ...]}
// Each check names a JSON pointer into ACTUAL, the expected value and a tolerance (rel_tol and/or
// abs_tol for numbers: |a - e| <= abs_tol + rel_tol |e|; strings and booleans must be equal). Prints
// one line per check and exits 1 if any fails, 2 if a file cannot be read.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace {

nlohmann::json read(const char* path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(std::string(path) + ": cannot open file");
  return nlohmann::json::parse(in);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: uhpc-compare-json EXPECTED.json ACTUAL.json\n");
    return 2;
  }
  nlohmann::json expected, actual;
  try {
    expected = read(argv[1]);
    actual = read(argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  int failed = 0, passed = 0;
  for (const auto& check : expected.at("checks")) {
    const std::string pointer = check.at("pointer").get<std::string>();
    const std::string why = check.value("why", "");
    const nlohmann::json::json_pointer ptr(pointer);
    if (!actual.contains(ptr)) {
      std::printf("FAIL %s: missing (%s)\n", pointer.c_str(), why.c_str());
      ++failed;
      continue;
    }
    const nlohmann::json& got = actual.at(ptr);
    const nlohmann::json& want = check.at("expected");
    bool ok;
    std::string detail;
    if (want.is_number()) {
      const double e = want.get<double>(), a = got.is_number() ? got.get<double>() : NAN;
      const double tol = check.value("abs_tol", 0.0) + check.value("rel_tol", 0.0) * std::abs(e);
      ok = std::isfinite(a) && std::abs(a - e) <= tol;
      char buf[160];
      std::snprintf(buf, sizeof buf, "got %.10g, expected %.10g +- %.3g", a, e, tol);
      detail = buf;
    } else {
      ok = got == want;
      detail = "got " + got.dump() + ", expected " + want.dump();
    }
    std::printf("%s %s: %s (%s)\n", ok ? "ok  " : "FAIL", pointer.c_str(), detail.c_str(), why.c_str());
    (ok ? passed : failed)++;
  }
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
