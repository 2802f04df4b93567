// Test helper: a scripted bus conversation (frames, corruptions, noise) and its oracle.
#pragma once

#include <cstdint>
#include <vector>

#include "pvtap/framing/framing_probe.h"
#include "pvtap/framing/stream_reassembler.h"
#include "random_frames.h"

namespace pvtap::test {

// BusItem: one thing put on the bus, at a known stream offset.
struct BusItem {
  enum class Kind { Frame, CorruptFrame, Noise } kind = Kind::Frame;
  std::uint64_t offset = 0;
  std::vector<std::uint8_t> bytes;
  Frame frame;                      // for frames
  bool structure_survives = false;  // for corrupt frames: the header still gives its length
  bool length_field_hit = false;    // for corrupt RTU frames: the function code or byte count
  std::size_t damaged_at = 0;       // for corrupt frames: the byte that was changed
};

// Whether byte `at` of an RTU frame decides its length: the function code, or the byte count
// of a reply (both dialects count at byte 2, GSL exceptions aside) or of a GSL 0x10 request.
inline bool decides_rtu_length(const Frame& f, std::size_t at) {
  if (f.dialect == Dialect::Ascii) return false;
  if (at == 1) return true;
  if (f.role == Role::Response) {
    const bool exception = f.dialect == Dialect::Gsl && (f.function & 0x80) != 0;
    const bool counted = f.dialect == Dialect::Hybrid || f.function == 0x03 || f.function == 0x04;
    return at == 2 && counted && !exception;
  }
  return at == 6 && f.dialect == Dialect::Gsl && f.function == 0x10;
}

// CapturedEvents: what a reassembler reported, copied out of the callbacks.
struct CapturedEvent {
  bool is_frame = false;
  std::uint64_t offset = 0;
  std::vector<std::uint8_t> bytes;
  FrameEvent frame;  // spans inside are not valid after the callback
};

class CapturingSink : public ReassemblerSink {
 public:
  void on_frame(const FrameEvent& e) override {
    events.push_back({true, e.offset, {e.bytes.begin(), e.bytes.end()}, e});
  }
  void on_noise(const NoiseEvent& e) override {
    events.push_back({false, e.offset, {e.bytes.begin(), e.bytes.end()}, {}});
  }
  std::vector<CapturedEvent> events;
};

struct ScriptOptions {
  std::size_t items = 30;
  unsigned noise_percent = 20;    // chance that noise precedes a frame
  unsigned corrupt_percent = 15;  // chance that a frame gets one byte changed
  DialectSet dialects = DialectSet::all();
};

// Builds a random conversation; a corrupted frame that still parses with a good check (a hex
// digit that changed case) counts as clean.
inline std::vector<BusItem> make_script(RandomFrames& gen, const ScriptOptions& o) {
  std::vector<BusItem> items;
  std::uint64_t offset = 0;
  for (std::size_t i = 0; i < o.items; ++i) {
    if (gen.pick(1, 100) <= o.noise_percent) {
      BusItem noise;
      noise.kind = BusItem::Kind::Noise;
      noise.offset = offset;
      const unsigned n = gen.pick(1, 24);
      for (unsigned k = 0; k < n; ++k)
        noise.bytes.push_back(static_cast<std::uint8_t>(gen.pick(0, 255)));
      offset += n;
      items.push_back(std::move(noise));
    }
    BusItem item;
    item.offset = offset;
    item.bytes = gen.next_wire(&item.frame);
    if (gen.pick(1, 100) <= o.corrupt_percent) {
      const std::size_t at = gen.pick(0, static_cast<unsigned>(item.bytes.size() - 1));
      item.bytes[at] = static_cast<std::uint8_t>(item.bytes[at] ^ gen.pick(1, 255));
      // A changed delimiter leaves the ASCII sum intact but breaks the frame all the same.
      const bool still_good = verify_check(item.bytes, item.frame.dialect).ok &&
                              parse_frame(item.bytes, item.frame.dialect, item.frame.role);
      if (!still_good) {
        item.kind = BusItem::Kind::CorruptFrame;
        item.length_field_hit = decides_rtu_length(item.frame, at);
        item.damaged_at = at;
        const RoleHint hint =
            item.frame.role == Role::Request ? RoleHint::Request : RoleHint::Response;
        // At a pinned start only structure counts, not the plausibility of the fields.
        const auto cands = frame_candidates(item.bytes, hint, o.dialects, Plausibility::Ignore);
        for (std::size_t c = 0; c < cands.size; ++c) {
          if (cands.items[c].length == item.bytes.size() &&
              cands.items[c].dialect == item.frame.dialect) {
            item.structure_survives = true;
          }
        }
      }
    }
    offset += item.bytes.size();
    items.push_back(std::move(item));
  }
  return items;
}

inline std::vector<std::uint8_t> concatenate(const std::vector<BusItem>& items) {
  std::vector<std::uint8_t> out;
  for (const auto& it : items) out.insert(out.end(), it.bytes.begin(), it.bytes.end());
  return out;
}

}  // namespace pvtap::test
