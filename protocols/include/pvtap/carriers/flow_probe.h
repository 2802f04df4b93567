// FlowProbe: holds the first bytes of a TCP or UDP flow until they show inverter frames (bare,
// or wrapped by a logger stick in Solarman V5) or Modbus/TCP ADUs, so that a capture with other
// traffic (SSH, HTTP, DNS) needs no port.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pvtap/carriers/solarman_v5_structure.h"
#include "pvtap/codec/dialect.h"
#include "pvtap/framing/stream_reassembler.h"

namespace pvtap {

class FlowProbe {
 public:
  // SolarmanV5: the flow's first bytes are a logger stick's V5 frame (decided before bare
  // RTU frames, which a V5 frame holds inside it).
  enum class Verdict { Undecided, Bus, Mbap, NotBus, SolarmanV5 };
  // Two good frames make a bus: one CRC that matches by chance in random data is plausible
  // within 16 KiB, two are not. Two pieces that are each whole MBAP ADUs (whole_mbap_adus)
  // make a Modbus/TCP flow, by the same reasoning.
  static constexpr unsigned kGoodFramesNeeded = 2;
  static constexpr std::size_t kMaxBytes = 16 * 1024;

  // ProbeItem: data or a gap, in arrival order, for replay once the flow is accepted.
  struct Item {
    Direction direction = Direction::Unknown;
    double time = 0;
    bool gap = false;
    std::uint64_t lost = 0;
    std::vector<std::uint8_t> bytes;
  };

  // `listed`: the flow is on a --port, so it carries bus traffic: V5 when its first bytes
  // are a V5 frame, Modbus/TCP when its first piece is whole MBAP ADUs, else bare frames.
  explicit FlowProbe(DialectSet dialects, bool listed = false);
  ~FlowProbe();
  FlowProbe(const FlowProbe&) = delete;
  FlowProbe& operator=(const FlowProbe&) = delete;

  Verdict add_data(Direction d, std::span<const std::uint8_t> bytes, double time);
  void add_gap(Direction d, std::uint64_t lost, double time);
  // At the end of the input a single good frame (or MBAP piece) is enough (a short capture
  // of one poll); the one with more evidence wins.
  Verdict final_verdict();

  const std::vector<Item>& items() const { return items_; }
  std::uint64_t bytes() const { return bytes_; }
  void clear();

 private:
  // GoodFrames: counts the frames with a good check the core's framing decision finds.
  struct GoodFrames : ReassemblerSink {
    void on_frame(const FrameEvent& e) override { count += e.check.ok ? 1u : 0u; }
    void on_noise(const NoiseEvent&) override {}
    unsigned count = 0;
  };
  StreamReassembler& stream(Direction d);
  // The V5 recognition of each direction's first bytes (solarman_v5_structure.h).
  solarman_v5::Recognition recognize_v5(Direction d, std::span<const std::uint8_t> bytes);
  bool v5_undecided() const;
  Verdict listed_verdict() const;

  DialectSet dialects_;
  std::vector<Item> items_;
  GoodFrames good_;
  std::array<std::unique_ptr<StreamReassembler>, kDirections> streams_;
  std::uint64_t bytes_ = 0;
  unsigned mbap_pieces_ = 0;
  bool first_piece_mbap_ = false;
  bool listed_;
  std::array<std::vector<std::uint8_t>, kDirections> v5_head_;
  std::array<solarman_v5::Recognition, kDirections> v5_{};
};

}  // namespace pvtap
