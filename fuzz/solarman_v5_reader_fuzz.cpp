// Fuzz target solarman_v5_reader: one direction of a logger stick's TCP flow, cut into pieces
// chosen by the fuzzer, with data lost between some of them. Asserts that the events tile the
// stream in order, that every frame opens with the start byte and closes with the end byte,
// that the reader holds at most one frame's worth of bytes, and that every byte is counted
// once when the stream ends. Its frames go through the pairing by sequence byte too: every
// request fed is handed on once or refused once, none is held after the end, and no RTU
// frame handed on is longer than a payload.
//
// Layout: records of length (1 byte), flags (bit 0: data is lost after the piece), bytes.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_input.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "pvtap/carriers/solarman_v5_reader.h"

namespace {

namespace v5 = pvtap::solarman_v5;

// What the pairing hands on, counted.
struct Released final : v5::ReleaseSink {
  void release(const v5::Release& r) override {
    PVTAP_FUZZ_CHECK(r.rtu.size() <= v5::kMaxPayload);
    if (r.kind == v5::Release::Kind::Request) ++requests;
    if (r.kind == v5::Release::Kind::Refused) ++refused;
  }
  std::uint64_t requests = 0;
  std::uint64_t refused = 0;
};

struct Pairing {
  Released released;
  v5::SolarmanV5Pairing pairing{1.0, released};
  std::uint64_t requests_fed = 0;
  double time = 0;
};

// Tiling: where the next event must start (the reader's own positions skip nothing).
void check_events(std::span<const v5::Event> events, std::uint64_t& next, Pairing& p) {
  for (const v5::Event& e : events) {
    if (e.kind == v5::Event::Kind::Frame) {
      const bool request = e.frame.kind == v5::FrameKind::Request && e.frame.rtu_length > 0;
      p.requests_fed += request ? 1 : 0;
      p.time += 0.25;
      p.pairing.frame(e.frame, p.time, e.offset);
    }
    PVTAP_FUZZ_CHECK(e.offset == next);
    PVTAP_FUZZ_CHECK(!e.bytes.empty());
    next += e.bytes.size();
    if (e.kind != v5::Event::Kind::Frame) continue;
    PVTAP_FUZZ_CHECK(e.bytes.front() == v5::kStart && e.bytes.back() == v5::kEnd);
    PVTAP_FUZZ_CHECK(e.frame.rtu_length + e.frame.quirk_bytes <= e.bytes.size());
  }
}

void check_totals(const v5::SolarmanV5Reader& r) {
  const v5::Totals& t = r.totals();
  PVTAP_FUZZ_CHECK(t.bytes_in == t.carrier_bytes + t.rtu_bytes + t.quirk_bytes + t.broken_bytes +
                                     t.noise_bytes + r.pending());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pvtap::fuzz::FuzzInput in(data, size);
  v5::SolarmanV5Reader reader;
  Pairing pairing;
  std::uint64_t next = 0;
  while (!in.empty()) {
    const std::uint8_t length = in.byte();
    const std::uint8_t flags = in.byte();
    check_events(reader.feed(in.take(length)), next, pairing);
    PVTAP_FUZZ_CHECK(reader.pending() <= v5::kOverhead + v5::kMaxPayload + 255);
    if (flags & 1u) check_events(reader.discontinuity(), next, pairing);
    check_totals(reader);
  }
  check_events(reader.finish(), next, pairing);
  PVTAP_FUZZ_CHECK(reader.pending() == 0);
  pairing.pairing.finish();
  PVTAP_FUZZ_CHECK(pairing.pairing.held() == 0);
  PVTAP_FUZZ_CHECK(pairing.released.requests + pairing.released.refused == pairing.requests_fed);
  check_totals(reader);
  return 0;
}
