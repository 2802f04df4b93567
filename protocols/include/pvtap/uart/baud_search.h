// A serial line's rate and format found passively from what a UART reads: which setting to
// try next, and when the search has settled. Sans-I/O: the tap applies the settings.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "pvtap/uart/parity_evidence.h"
#include "pvtap/uart/uart_format.h"

namespace pvtap {

// LineSetting: what a serial receiver is set to.
struct LineSetting {
  std::uint32_t baud = 9600;
  UartFormat format;
};

// LineByte: one byte as the receiver delivered it. A tty marks framing and parity errors
// alike (PARMRK), so they are one flag here.
struct LineByte {
  std::uint8_t value = 0;
  bool error = false;
  bool is_break = false;
};

struct BaudSearchOptions {
  // A setting is given up after this many bytes without a request and reply that check...
  std::uint64_t dwell_bytes = 64;
  // ...or this long (seconds) after its first byte. A quiet line keeps the setting.
  double dwell_seconds = 2.5;
  // Once settled: this many bytes in a row, or this long (seconds) of bytes, without a frame
  // that checks restart the search.
  std::uint64_t lost_after_bytes = 256;
  double lost_after_seconds = 5.0;
};

// BaudSearch: cycles the standard rates at 8N1 (a UART at 8N1 reads the data bits of an 8E1
// or 8O1 line right, and which bytes fail tells the parity), settles when a request and its
// reply both check, confirms a parity found that way with the parity set, and searches
// again when a settled line stops giving frames that check.
class BaudSearch {
 public:
  explicit BaudSearch(BaudSearchOptions options = {});
  ~BaudSearch();
  BaudSearch(const BaudSearch&) = delete;
  BaudSearch& operator=(const BaudSearch&) = delete;

  // The rates tried, in the order tried: the common ones first.
  static std::span<const std::uint32_t> rates();

  const LineSetting& setting() const { return setting_; }
  bool settled() const { return phase_ == Phase::Settled; }
  // Settings applied so far, the first one included.
  std::uint64_t settings_tried() const { return tried_; }
  // Times the search started again after it had settled.
  std::uint64_t searches_again() const { return again_; }

  // Bytes read at setting() at `time` (seconds). True when setting() changed: the receiver
  // must be set to it, and bytes it read at the old setting are of no use.
  bool feed(std::span<const LineByte> bytes, double time);
  // Time passes (a dwell that saw traffic ends on time even when the bytes stop).
  bool tick(double time);

 private:
  enum class Phase : std::uint8_t { Search, Confirm, Settled };
  struct Dwell;

  void feed_byte(const LineByte& b, double time);
  bool decide(double time);
  bool dwell_over(double time) const;
  void apply(LineSetting setting, Phase phase);
  void next_rate();

  BaudSearchOptions options_;
  Phase phase_ = Phase::Search;
  std::size_t rate_index_ = 0;
  LineSetting setting_;
  std::unique_ptr<Dwell> dwell_;
  std::uint64_t tried_ = 0;
  std::uint64_t again_ = 0;
};

}  // namespace pvtap
