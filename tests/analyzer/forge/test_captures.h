// The captures the analyzer's end-to-end tests read, each with the audit it must give.
#pragma once

#include <string>

namespace pvtap::forge {

// Writes every test capture into `dir` (which must exist), each as NAME.pcap (or .pcapng,
// .bin) with NAME.expect.json next to it, plus the bad inputs and a user register map.
void write_test_captures(const std::string& dir);

// A gateway capture of at least `megabytes` MB for the throughput benchmark, written as it
// is generated (memory stays small).
void write_bench_capture(const std::string& path, unsigned megabytes);
// The same poll rounds through a Solarman V5 logger stick on port 8899.
void write_v5_bench_capture(const std::string& path, unsigned megabytes);

}  // namespace pvtap::forge
