// A logic-analyzer recording read through libsigrok, streamed chunk by chunk: sigrok session
// files (.sr) by its session loading, any other file by the input module that recognises it
// (VCD, logic CSV, ...). The session is never held whole.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pvtap::analyzer {

// LogicChannel: a logic channel of the recording, as the file names it.
struct LogicChannel {
  std::string name;
  unsigned index = 0;  // its bit in every sample (sample bytes are little-endian)
};

// LogicSink: receives a recording's channels, then its samples as the file yields them.
class LogicSink {
 public:
  virtual ~LogicSink() = default;
  // Once, before the first samples: the logic channels and the sample rate (0: unknown).
  virtual void begin(const std::vector<LogicChannel>& channels, double sample_rate) = 0;
  // `data` holds whole samples of `unitsize` bytes each.
  virtual void samples(std::span<const std::uint8_t> data, unsigned unitsize) = 0;
  // False once the sink has seen enough: reading stops early.
  virtual bool wants_more() const { return true; }
};

// Reads `path` from its start into `sink`; the one-line reason when it cannot be read (not a
// recording libsigrok knows, unreadable); empty when done. Each call reads afresh.
// `sample_rate`: given in place of the recording's own (0: the recording's).
std::string read_logic_file(const std::string& path, LogicSink& sink, double sample_rate = 0);

}  // namespace pvtap::analyzer
