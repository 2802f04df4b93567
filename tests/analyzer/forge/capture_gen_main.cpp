// pvtap-capture-gen: writes deterministic captures with known content.
//   pvtap-capture-gen tests DIR           every end-to-end test capture and its expected audit
//   pvtap-capture-gen bench FILE MB       a gateway capture of at least MB megabytes
//   pvtap-capture-gen bench-v5 FILE MB    the same through a Solarman V5 logger stick
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "test_captures.h"

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  try {
    if (what == "tests" && argc == 3) {
      pvtap::forge::write_test_captures(argv[2]);
    } else if (what == "bench" && argc == 4) {
      pvtap::forge::write_bench_capture(argv[2],
                                        static_cast<unsigned>(std::strtoul(argv[3], nullptr, 10)));
    } else if (what == "bench-v5" && argc == 4) {
      pvtap::forge::write_v5_bench_capture(
          argv[2], static_cast<unsigned>(std::strtoul(argv[3], nullptr, 10)));
    } else {
      std::fprintf(stderr, "usage: pvtap-capture-gen tests DIR | bench|bench-v5 FILE MB\n");
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pvtap-capture-gen: %s\n", e.what());
    return 1;
  }
  return 0;
}
