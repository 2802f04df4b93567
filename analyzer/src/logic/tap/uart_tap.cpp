// UartTap: runs to characters to bus chunks, one character a chunk, stamped with its end.
#include "logic/tap/uart_tap.h"

#include <cmath>

namespace pvtap::analyzer {

namespace {

// The UART channels' bits, then the DE channels'.
std::vector<unsigned> bits_of(const std::vector<TappedChannel>& channels,
                              const std::vector<LogicChannel>& drivers) {
  std::vector<unsigned> bits;
  for (const TappedChannel& c : channels) bits.push_back(c.channel.index);
  for (const LogicChannel& d : drivers) bits.push_back(d.index);
  return bits;
}

std::vector<std::string> names_of(const std::vector<LogicChannel>& channels) {
  std::vector<std::string> names;
  for (const LogicChannel& c : channels) names.push_back(c.name);
  return names;
}

double char_samples_of(const DetectedLine& d, double sample_rate) {
  return sample_rate / d.line.baud * (d.line.format.bits_per_char() + 1);
}

double char_samples(const std::vector<TappedChannel>& channels, double sample_rate) {
  if (channels.empty()) return 0;
  const UartLine& line = channels.front().line.line;
  return sample_rate / line.baud * line.format.bits_per_char();
}

// The side of a bus on two channels: requests on the first, replies on the second.
Direction side_direction(const TappedChannel& t) {
  if (t.pair < 0) return Direction::Unknown;
  return t.side == 0 ? Direction::ToSlave : Direction::FromSlave;
}

SerialLineReport settings_of(const TappedChannel& c) {
  SerialLineReport r;
  const DetectedLine& d = c.line;
  r.baud = d.baud.baud;
  r.measured_baud = d.baud.measured;
  r.deviation = d.baud.deviation;
  r.clock_deviations = std::abs(d.baud.deviation) > BaudEstimate::kSnapTolerance ? 1 : 0;
  r.parity = parity_name(d.line.format.parity);
  r.data_bits = d.line.format.data_bits;
  r.stop_bits = d.line.format.stop_bits;
  r.inverted = d.line.format.inverted;
  r.channel = c.channel.name;
  return r;
}

}  // namespace

UartTap::UartTap(std::vector<TappedChannel> channels, std::vector<LogicChannel> drivers,
                 double sample_rate)
    : sample_rate_(sample_rate),
      scanner_(bits_of(channels, drivers)),
      turnaround_(names_of(drivers), sample_rate, char_samples(channels, sample_rate)) {
  slots_.reserve(channels.size());
  for (TappedChannel& c : channels) {
    if (c.pair >= 0) pairs_.resize(std::max(pairs_.size(), static_cast<std::size_t>(c.pair) + 1));
    SerialLineReport report = settings_of(c);
    UartDecoder decoder(c.line.line);
    DriverGlitchFilter filter(c.line.line);
    slots_.push_back(Slot{std::move(c), decoder, std::move(filter), std::move(report)});
  }
}

void UartTap::begin(const std::vector<LogicChannel>&, double) {}

void UartTap::samples(std::span<const std::uint8_t> data, unsigned unitsize) {
  ++chunks_;
  scanner_.scan(data, unitsize, *this);
}

void UartTap::run(std::size_t slot, SampleRun run) {
  if (slot >= slots_.size()) return turnaround_.driver_run(slot - slots_.size(), run);
  slots_[slot].decoder.feed(run, characters_);
  if (!characters_.empty()) deliver(slots_[slot]);
  if (slots_[slot].tapped.pair >= 0) feed_pair(slots_[slot]);
}

// Nothing earlier can still come from a channel than its held run or, the decoder being in a
// character perhaps, a character before the samples it has read.
void UartTap::feed_pair(Slot& s) {
  const double behind =
      static_cast<double>(s.decoder.position()) - char_samples_of(s.tapped.line, sample_rate_);
  const std::uint64_t read = behind > 0 ? static_cast<std::uint64_t>(behind) : 0;
  DirectionMerge& merge = pairs_[static_cast<std::size_t>(s.tapped.pair)];
  merge.advance(s.tapped.side, s.glitch_filter.held_from(read));
  merge.release(merged_);
  feed_merged(*s.tapped.bus);
}

// The pair's characters released in time order, each a chunk stamped with its end.
void UartTap::feed_merged(BusSession& bus) {
  for (const DirectedCharacter& d : merged_) {
    const auto byte = static_cast<std::uint8_t>(d.character.value);
    const double end = static_cast<double>(d.character.end) / sample_rate_;
    bus.feed(BusChunk{std::span(&byte, 1), end, d.direction});
  }
  merged_.clear();
}

// A break carries no byte; a character with a line error still does (the frame around it
// then fails its check, as it would for a receiver). Characters go through the glitch filter,
// which holds each run until the line has been quiet for 3.5 characters.
void UartTap::deliver(Slot& s) {
  for (const UartCharacter& c : characters_) {
    if (c.is_break) {
      report_line_error(s, c);
      continue;
    }
    s.glitch_filter.feed(c, bus_characters_, glitches_);
  }
  characters_.clear();
  feed_bus(s, &s == &slots_.front());
}

// Glitches have their own event; a character that stays on the bus, or a break, gets this one.
// Both go through the bus's session, which counts them as it counts every other event.
void UartTap::report_line_error(const Slot& s, const UartCharacter& c) {
  using Kind = LineErrorKind;
  const Kind kind = c.is_break                          ? Kind::Break
                    : c.framing_error && c.parity_error ? Kind::FramingAndParity
                    : c.framing_error                   ? Kind::Framing
                                                        : Kind::Parity;
  const double rate = sample_rate_;
  s.tapped.bus->line_error(SessionLineError{
      static_cast<double>(c.start) / rate, static_cast<double>(c.end - c.start) / rate,
      static_cast<std::uint8_t>(c.value), kind, side_direction(s.tapped)});
}

void UartTap::feed_bus(Slot& s, bool first) {
  for (const DriverGlitch& g : glitches_) {
    const UartCharacter& c = g.character;
    s.tapped.bus->driver_glitch(SessionDriverGlitch{
        static_cast<double>(c.start) / sample_rate_, static_cast<std::uint8_t>(c.value),
        g.switch_on, c.framing_error, c.parity_error, side_direction(s.tapped)});
  }
  for (const UartCharacter& c : bus_characters_) {
    if (c.framing_error || c.parity_error) report_line_error(s, c);
    if (first) turnaround_.character(c);
    if (s.tapped.pair >= 0) {
      pairs_[static_cast<std::size_t>(s.tapped.pair)].add(s.tapped.side, c);
      continue;
    }
    const auto byte = static_cast<std::uint8_t>(c.value);
    const double end = static_cast<double>(c.end) / sample_rate_;
    s.tapped.bus->feed(BusChunk{std::span(&byte, 1), end, Direction::Unknown});
  }
  glitches_.clear();
  bus_characters_.clear();
}

void UartTap::finish() {
  scanner_.finish(*this);
  for (Slot& s : slots_) {
    s.decoder.finish(characters_);
    deliver(s);
    s.glitch_filter.flush(bus_characters_, glitches_);
    feed_bus(s, &s == &slots_.front());
  }
  // Every pair's last characters, each to its bus.
  for (Slot& s : slots_) {
    if (s.tapped.pair < 0 || s.tapped.side != 0) continue;
    pairs_[static_cast<std::size_t>(s.tapped.pair)].finish(merged_);
    feed_merged(*s.tapped.bus);
  }
}

double UartTap::end_time() const {
  return slots_.empty() ? 0.0
                        : static_cast<double>(slots_.front().decoder.position()) / sample_rate_;
}

std::vector<TappedLine> UartTap::lines() const {
  std::vector<TappedLine> out;
  for (const Slot& s : slots_) out.push_back(TappedLine{s.tapped.bus_name, s.report});
  if (!out.empty()) out.front().line.turnarounds = turnaround_.turnarounds();
  return out;
}

}  // namespace pvtap::analyzer
