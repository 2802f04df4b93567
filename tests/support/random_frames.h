// Test and benchmark helper: random valid frames of every kind of every dialect.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "frame_builders.h"
#include "pvtap/codec/frame.h"
#include "pvtap/codec/frame_codec.h"

namespace pvtap::test {

class RandomFrames {
 public:
  explicit RandomFrames(std::uint32_t seed, DialectSet dialects = DialectSet::all())
      : rng_(seed), dialects_(dialects) {}

  Frame next() {
    for (;;) {
      const auto d = static_cast<Dialect>(pick(0, 2));
      if (!dialects_.contains(d)) continue;
      if (d == Dialect::Ascii) return ascii();
      return d == Dialect::Hybrid ? hybrid() : gsl();
    }
  }

  std::vector<std::uint8_t> next_wire(Frame* frame = nullptr) {
    const Frame f = next();
    if (frame) *frame = f;
    return encode_frame(f);
  }

  unsigned pick(unsigned lo, unsigned hi) {
    return std::uniform_int_distribution<unsigned>(lo, hi)(rng_);
  }
  std::mt19937& rng() { return rng_; }

 private:
  std::uint16_t word() { return static_cast<std::uint16_t>(pick(0, 0xFFFF)); }
  std::uint8_t u8(unsigned lo, unsigned hi) { return static_cast<std::uint8_t>(pick(lo, hi)); }
  void words(Frame& f, unsigned n) {
    for (unsigned i = 0; i < n; ++i) f.words.push_back(word());
  }
  Frame ascii() {
    const bool request = pick(0, 1) == 0;
    Frame f = frame_of(Dialect::Ascii, request ? Role::Request : Role::Response, u8(0, 0x1F), 'R');
    f.start = static_cast<std::uint16_t>(pick(0, 0x100) * 2);
    if (request)
      f.count = static_cast<std::uint16_t>(pick(1, 16));
    else
      words(f, pick(1, 16));
    return f;
  }

  Frame hybrid() {
    static constexpr std::uint8_t kReads[] = {0x11, 0x12, 0x16, 0x17, 0x1F};
    const std::uint8_t station = u8(1, 0xFE);
    switch (pick(0, 5)) {
      case 0: {  // read request
        Frame f = frame_of(Dialect::Hybrid, Role::Request, station, kReads[pick(0, 4)]);
        if (f.function == 0x11 && pick(0, 1)) f.station = 0xFF;
        f.start = static_cast<std::uint16_t>(0x1000 + pick(0, 0x60));
        f.count = static_cast<std::uint16_t>(pick(1, 0x30));
        return f;
      }
      case 1: {  // write request
        Frame f = frame_of(Dialect::Hybrid, Role::Request, station, 0x18);
        f.start = static_cast<std::uint16_t>(0x1024 + pick(0, 0x26));
        f.words.push_back(word());
        return f;
      }
      case 2:
      case 3: {  // read reply
        Frame f = frame_of(Dialect::Hybrid, Role::Response, station, kReads[pick(0, 3)]);
        f.device = DeviceNumber{u8(0x11, 0x41), pick(0, 0xFFFFFF)};
        words(f, pick(0, 48));
        f.byte_count = static_cast<std::uint8_t>(4 + 2 * f.words.size());
        return f;
      }
      case 4: {  // write echo
        Frame f = frame_of(Dialect::Hybrid, Role::Response, station, 0x18);
        f.device = DeviceNumber{0x31, pick(0, 0xFFFFFF)};
        f.byte_count = 8;
        f.start = static_cast<std::uint16_t>(0x1024 + pick(0, 0x26));
        f.words.push_back(word());
        return f;
      }
      default: {  // restore confirmation or error reply
        Frame f = frame_of(Dialect::Hybrid, Role::Response, station, pick(0, 1) ? 0x1F : 0xFF);
        f.device = DeviceNumber{0x32, pick(0, 0xFFFFFF)};
        f.byte_count = 8;
        f.start = f.function == 0xFF ? 0x1000 : 0x1024;
        f.count = f.function == 0xFF ? 0x00FF : 0x007B;
        return f;
      }
    }
  }

  Frame gsl() {
    const std::uint8_t station = u8(1, 247);
    switch (pick(0, 6)) {
      case 0: {
        Frame f = frame_of(Dialect::Gsl, Role::Request, station, pick(0, 3) ? 0x03 : 0x04);
        f.start = static_cast<std::uint16_t>(1000 + pick(0, 100));
        f.count = static_cast<std::uint16_t>(pick(1, 60));
        return f;
      }
      case 1:
      case 2: {
        Frame f = frame_of(Dialect::Gsl, Role::Response, station, pick(0, 3) ? 0x03 : 0x04);
        words(f, pick(1, 60));
        f.byte_count = static_cast<std::uint8_t>(2 * f.words.size());
        return f;
      }
      case 3: {
        Frame f =
            frame_of(Dialect::Gsl, pick(0, 1) ? Role::Request : Role::Response, station, 0x06);
        f.start = static_cast<std::uint16_t>(1250 + pick(0, 2));
        f.words.push_back(word());
        return f;
      }
      case 4: {
        Frame f = frame_of(Dialect::Gsl, Role::Request, station, 0x10);
        f.start = 1500;
        words(f, pick(1, 6));
        f.count = static_cast<std::uint16_t>(f.words.size());
        f.byte_count = static_cast<std::uint8_t>(2 * f.words.size());
        return f;
      }
      case 5: {
        Frame f = frame_of(Dialect::Gsl, Role::Response, station, 0x10);
        f.start = 1500;
        f.count = static_cast<std::uint16_t>(pick(1, 6));
        return f;
      }
      default: {
        static constexpr std::uint8_t kEx[] = {0x83, 0x84, 0x86, 0x90};
        static constexpr std::uint8_t kCodes[] = {1, 2, 3, 6};
        Frame f = frame_of(Dialect::Gsl, Role::Response, station, kEx[pick(0, 3)]);
        f.exception_code = kCodes[pick(0, 3)];
        return f;
      }
    }
  }

  std::mt19937 rng_;
  DialectSet dialects_;
};

}  // namespace pvtap::test
