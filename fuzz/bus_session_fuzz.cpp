// Fuzz target bus_session: the core's whole pipeline for one bus (reassembly, parsing,
// pairing, decoding, timing) on chunks, turns, losses and restarts chosen by the fuzzer.
// Asserts the byte accounting over all directions and that the report stays bounded: examples
// capped, one summary per station address at most.
#include <cstddef>
#include <cstdint>

#include "chunk_script.h"
#include "fuzz_input.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/session/bus_session.h"

namespace {

using pvtap::fuzz::ScriptStep;
using pvtap::fuzz::StepKind;

class CountingSink : public pvtap::BusSessionSink {
 public:
  void on_frame(const pvtap::SessionFrame& f) override {
    PVTAP_FUZZ_CHECK(!f.bytes.empty());
    PVTAP_FUZZ_CHECK(f.bytes.size() <= pvtap::fuzz::max_frame_length(f.dialect));
    PVTAP_FUZZ_CHECK(f.id == frames);
    PVTAP_FUZZ_CHECK(!f.request_id || *f.request_id < f.id);
    // Every frame was sent, so it carries at least its header (it is paired and counted by
    // it), also when it does not parse: damaged, or sent with a good check and a byte count
    // that lies (tests/corpus/bus_session/crash-good-check-hybrid-reply-too-short). Values come
    // only from a frame with a good check, and none from a frame that does not parse.
    PVTAP_FUZZ_CHECK(f.frame != nullptr);
    PVTAP_FUZZ_CHECK(!f.values_trusted || f.check.ok);
    PVTAP_FUZZ_CHECK(f.parse_error.empty() || f.values.empty());
    frame_bytes += f.bytes.size();
    ++frames;
  }
  void on_noise(const pvtap::SessionNoise& n) override {
    PVTAP_FUZZ_CHECK(!n.noise.bytes.empty());
    noise_bytes += n.noise.bytes.size();
  }

  std::uint64_t frame_bytes = 0;
  std::uint64_t noise_bytes = 0;
  std::uint64_t frames = 0;
};

void apply(pvtap::BusSession& session, const ScriptStep& step, std::uint64_t& fed) {
  const auto& c = step.chunk;
  switch (step.kind) {
    case StepKind::Chunk:
      session.feed(c);
      fed += c.bytes.size();
      break;
    case StepKind::Idle:
      session.idle(c.time);
      break;
    case StepKind::Discontinuity:
      session.restart(c.direction);
      break;
    case StepKind::EndTurn:
      session.end_turn(c.direction);
      break;
    case StepKind::DataLost:
      session.data_lost(c.direction, c.time, c.bytes.size());
      break;
  }
}

void check_report(const pvtap::BusSession& session, const CountingSink& sink, std::uint64_t fed) {
  const auto t = session.totals();
  PVTAP_FUZZ_CHECK(t.bytes_in == fed);
  PVTAP_FUZZ_CHECK(t.frame_bytes == sink.frame_bytes);
  PVTAP_FUZZ_CHECK(t.noise_bytes == sink.noise_bytes);
  PVTAP_FUZZ_CHECK(t.frame_bytes + t.noise_bytes <= t.bytes_in);
  const auto report = session.report();
  PVTAP_FUZZ_CHECK(report.bad_check_examples.size() <= pvtap::BusReport::kMaxExamples);
  PVTAP_FUZZ_CHECK(report.timeout_examples.size() <= pvtap::BusReport::kMaxExamples);
  PVTAP_FUZZ_CHECK(report.unsolicited_examples.size() <= pvtap::BusReport::kMaxExamples);
  PVTAP_FUZZ_CHECK(report.stations.size() <= 256);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const pvtap::RegisterDecoder decoder;
  pvtap::fuzz::FuzzInput in(data, size);
  const auto o = pvtap::fuzz::read_script_options(in);
  pvtap::BusSessionOptions options;
  options.reassembler.dialects = o.dialects;
  options.reassembler.baud = o.baud;
  options.reassembler.timestamps = o.trust;
  options.has_timestamps = o.trust != pvtap::TimestampTrust::Untrusted;
  CountingSink sink;
  pvtap::BusSession session(options, decoder, sink);
  pvtap::fuzz::ChunkScript script(in);
  ScriptStep step;
  std::uint64_t fed = 0;
  std::size_t steps = 0;
  while (script.next(step)) {
    apply(session, step, fed);
    // The report is rebuilt now and then, not after every step (it copies every station).
    if (++steps % 64 == 0) check_report(session, sink, fed);
  }
  session.finish();
  check_report(session, sink, fed);
  const auto t = session.totals();
  PVTAP_FUZZ_CHECK(t.bytes_in == t.frame_bytes + t.noise_bytes);
  return 0;
}
