// BaudSearch: one dwell per setting, judged by the frames that check and the bytes that fail.
#include "pvtap/uart/baud_search.h"

#include <array>
#include <optional>

#include "checked_pair_watch.h"
#include "pvtap/framing/stream_reassembler.h"

namespace pvtap {
namespace {

// Inverter and meter buses run at 9600 or 19200 far more often than at anything else.
constexpr std::array<std::uint32_t, 8> kRates{9600, 19200, 4800, 38400, 2400, 57600, 115200, 1200};

ReassemblerOptions reassembler_options(const LineSetting& s) {
  ReassemblerOptions o;
  o.baud = s.baud;
  o.bits_per_char = s.format.bits_per_char();
  // A tty hands bytes over in batches: their times cannot tell where frames end.
  o.timestamps = TimestampTrust::Untrusted;
  return o;
}

}  // namespace

// Dwell: what the receiver read since the setting was applied.
struct BaudSearch::Dwell {
  explicit Dwell(const LineSetting& s) : reassembler(reassembler_options(s), watch) {}
  CheckedPairWatch watch;
  StreamReassembler reassembler;
  ParityEvidence evidence;
  std::uint64_t bytes = 0;
  std::optional<double> first_time;
  // A setting whose frames check, but whose pair has not come yet, is listened to twice as long.
  bool extended = false;
  std::uint64_t since_good = 0;  // bytes since the last frame that checked
  std::uint64_t good_seen = 0;
  double bad_since = 0;  // the time of the first byte since the last frame that checked
};

BaudSearch::BaudSearch(BaudSearchOptions options) : options_(options) {
  setting_.baud = kRates[0];
  apply(setting_, Phase::Search);
}

BaudSearch::~BaudSearch() = default;

std::span<const std::uint32_t> BaudSearch::rates() {
  return kRates;
}

void BaudSearch::apply(LineSetting setting, Phase phase) {
  setting_ = setting;
  phase_ = phase;
  dwell_ = std::make_unique<Dwell>(setting_);
  ++tried_;
}

void BaudSearch::next_rate() {
  rate_index_ = (rate_index_ + 1) % kRates.size();
  apply(LineSetting{kRates[rate_index_], UartFormat{}}, Phase::Search);
}

void BaudSearch::feed_byte(const LineByte& b, double time) {
  Dwell& d = *dwell_;
  if (!d.first_time) d.first_time = time;
  ++d.bytes;
  if (!b.is_break) d.evidence.add(b.value, b.error);
  // A break delivers no byte to the frames: it is a line condition, not a character.
  if (!b.is_break) d.reassembler.feed(BusChunk{std::span(&b.value, 1), time, Direction::Unknown});
  if (d.watch.good_frames != d.good_seen) {
    d.good_seen = d.watch.good_frames;
    d.since_good = 0;
  } else if (++d.since_good == 1) {
    d.bad_since = time;
  }
}

bool BaudSearch::feed(std::span<const LineByte> bytes, double time) {
  bool changed = false;
  for (const LineByte& b : bytes) {
    feed_byte(b, time);
    // Bytes after a change were read at the old setting: the caller drops them.
    if (decide(time)) changed = true;
    if (changed) break;
  }
  return changed;
}

bool BaudSearch::tick(double time) {
  return decide(time);
}

bool BaudSearch::dwell_over(double time) const {
  const Dwell& d = *dwell_;
  const std::uint64_t scale = d.extended ? 2 : 1;
  if (d.bytes >= options_.dwell_bytes * scale) return true;
  return d.first_time &&
         time - *d.first_time >= options_.dwell_seconds * static_cast<double>(scale);
}

bool BaudSearch::decide(double time) {
  Dwell& d = *dwell_;
  if (phase_ == Phase::Settled) {
    // A slow receiver on a fast line reads few bytes: the time since the last good frame
    // tells as well.
    const bool lost = d.since_good >= options_.lost_after_bytes ||
                      (d.since_good > 0 && time - d.bad_since >= options_.lost_after_seconds);
    if (!lost) return false;
    ++again_;
    rate_index_ = kRates.size() - 1;  // next_rate() starts the cycle from the top
    next_rate();
    return true;
  }
  const bool errors_rare = d.evidence.errors() * 16 <= d.evidence.bytes();
  if (d.watch.pair) {
    const std::optional<Parity> parity = d.evidence.verdict();
    if (phase_ == Phase::Search && parity) {
      LineSetting confirm = setting_;
      confirm.format.parity = *parity;
      apply(confirm, Phase::Confirm);
      return true;
    }
    if (errors_rare || phase_ == Phase::Search) {
      phase_ = Phase::Settled;
      return false;
    }
  }
  if (!dwell_over(time)) return false;
  if (d.watch.good_frames > 0 && !d.extended) {
    d.extended = true;
    return false;
  }
  next_rate();
  return true;
}

}  // namespace pvtap
