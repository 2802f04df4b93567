#include "serial_render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pvtap::forge {
namespace {

// TimedByte: one bus byte and when its last bit ended.
struct TimedByte {
  std::uint8_t value;
  double end;
  std::size_t item;
};

std::vector<TimedByte> timed_bytes(const BusPlan& plan) {
  std::vector<TimedByte> out;
  for (std::size_t i = 0; i < plan.items().size(); ++i) {
    const BusItem& item = plan.items()[i];
    for (std::size_t k = 0; k < item.bytes.size(); ++k) {
      out.push_back(
          TimedByte{item.bytes[k], item.start + static_cast<double>(k + 1) * plan.char_time(), i});
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const TimedByte& a, const TimedByte& b) { return a.end < b.end; });
  return out;
}

void put32be(Bytes& b, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) b.push_back(static_cast<std::uint8_t>(v >> shift));
}

Bytes rtac_header(double time, std::uint8_t event) {
  Bytes h;
  const double seconds = std::floor(time);
  put32be(h, static_cast<std::uint32_t>(seconds));
  put32be(h, static_cast<std::uint32_t>(std::lround((time - seconds) * 1e6)));
  h.push_back(event);
  h.push_back(0x19);  // CTS, RTS, DTR
  h.push_back(0x00);
  h.push_back(0x00);
  return h;
}

}  // namespace

void write_timer_chunks(const BusPlan& plan, CaptureWriter& out, double tick) {
  const std::vector<TimedByte> bytes = timed_bytes(plan);
  Bytes chunk;
  double chunk_end = 0;
  for (const TimedByte& b : bytes) {
    const double end = std::ceil(b.end / tick) * tick;
    if (!chunk.empty() && end != chunk_end) {
      out.write(chunk_end, chunk);
      chunk.clear();
    }
    chunk_end = end;
    chunk.push_back(b.value);
  }
  if (!chunk.empty()) out.write(chunk_end, chunk);
}

void write_rtac_records(const BusPlan& plan, CaptureWriter& out, std::size_t chunk,
                        const std::vector<std::size_t>& dropped) {
  constexpr std::uint8_t kDataRx = 0x02;
  constexpr std::uint8_t kDataLost = 0x05;
  const std::vector<TimedByte> bytes = timed_bytes(plan);
  Bytes record;
  double last_end = 0;
  bool loss_pending = false;
  const auto flush = [&] {
    if (record.size() <= 12) return;
    out.write(last_end, record);
    record.clear();
  };
  for (const TimedByte& b : bytes) {
    const bool drop = std::find(dropped.begin(), dropped.end(), b.item) != dropped.end();
    if (drop) {
      flush();
      loss_pending = true;
      continue;
    }
    if (loss_pending) {
      out.write(last_end, rtac_header(last_end, kDataLost));
      loss_pending = false;
    }
    if (record.empty()) record = rtac_header(b.end, kDataRx);
    record.push_back(b.value);
    last_end = b.end;
    if (record.size() == 12 + chunk) flush();
  }
  flush();
}

void write_raw_dump(const BusPlan& plan, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error("cannot write " + path);
  for (const TimedByte& b : timed_bytes(plan)) std::fputc(b.value, f);
  std::fclose(f);
}

}  // namespace pvtap::forge
