#include "logic/logic_signals.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "sim_random.h"

namespace pvtap::sim {
namespace {

// Builds one channel from levels set at times (µs, ascending), each edge moved by the jitter.
class SignalBuilder {
 public:
  SignalBuilder(std::string name, bool idle, double rate, double jitter, SimRandom& random)
      : random_(random), rate_(rate), jitter_(jitter) {
    out_.name = std::move(name);
    out_.initial = idle;
    level_ = idle;
  }

  void set(double at, bool level) {
    if (level == level_) return;
    level_ = level;
    const double moved = at + jitter_ * (2.0 * random_.unit() - 1.0);
    const auto sample =
        static_cast<std::uint64_t>(std::llround(std::max(0.0, moved) * rate_ / 1e6));
    // Two flips on one sample cancel; a flip never goes back before the one before it.
    if (!out_.toggles.empty() && sample <= out_.toggles.back()) {
      out_.toggles.pop_back();
      return;
    }
    out_.toggles.push_back(sample);
  }

  ChannelSignal take() { return std::move(out_); }

 private:
  SimRandom& random_;
  double rate_, jitter_;
  bool level_ = true;
  ChannelSignal out_;
};

// The line levels of one character from `start` (mark = true), before any inversion.
void put_character(SignalBuilder& b, const DrivenCharacter& c, const UartFormat& f, double bit,
                   bool invert) {
  unsigned ones = 0;
  b.set(c.start, invert);  // start bit: space
  for (unsigned i = 0; i < f.data_bits; ++i) {
    const bool one = (c.value >> i) & 1u;
    ones += one ? 1 : 0;
    b.set(c.start + bit * (1 + i), one != invert);
  }
  unsigned next = 1 + f.data_bits;
  if (f.parity != Parity::None) {
    const bool parity = f.parity == Parity::Even ? (ones & 1u) : !(ones & 1u);
    b.set(c.start + bit * next++, parity != invert);
  }
  b.set(c.start + bit * next, !invert);  // stop bits: mark
}

// One item on a line: a character, a glitch, or a driver switching on or off (--undriven space).
struct Timed {
  double at;
  const DrivenCharacter* character = nullptr;
  const GlitchPulse* glitch = nullptr;
  const DrivenSpan* span = nullptr;  // switching on at `at` (else off, when `released`)
  bool released = false;
};

// Spans that overlap (a reply whose driver comes on before the request's is released) are one.
std::vector<DrivenSpan> merged_spans(std::vector<DrivenSpan> spans) {
  std::sort(spans.begin(), spans.end(),
            [](const DrivenSpan& x, const DrivenSpan& y) { return x.on < y.on; });
  std::vector<DrivenSpan> out;
  for (const DrivenSpan& s : spans) {
    if (!out.empty() && s.on <= out.back().off) {
      out.back().off = std::max(out.back().off, s.off);
      continue;
    }
    out.push_back(s);
  }
  return out;
}

ChannelSignal uart_channel(const std::string& name, const LogicLayout& l, const LogicOptions& o,
                           bool master, bool slave, bool bus_line, SimRandom& random) {
  const bool inv = o.format.inverted;
  const bool undriven = bus_line && o.undriven_space;
  SignalBuilder b(name, undriven ? inv : !inv, o.sample_rate, l.bit * o.jitter_pct / 100.0, random);
  std::vector<Timed> items;
  for (const DrivenCharacter& c : l.characters)
    if (c.master ? master : slave) items.push_back({c.start, &c});
  if (bus_line)
    for (const GlitchPulse& g : l.glitches) items.push_back({g.start, nullptr, &g});
  const std::vector<DrivenSpan> spans =
      undriven ? merged_spans(l.driven) : std::vector<DrivenSpan>{};
  for (const DrivenSpan& s : spans) {
    items.push_back({s.on, nullptr, nullptr, &s, false});
    items.push_back({s.off, nullptr, nullptr, &s, true});
  }
  std::stable_sort(items.begin(), items.end(),
                   [](const Timed& x, const Timed& y) { return x.at < y.at; });
  for (const Timed& t : items) {
    if (t.character) {
      put_character(b, *t.character, o.format, l.bit, inv);
    } else if (t.glitch) {
      b.set(t.at, inv);
      b.set(t.at + l.bit * t.glitch->bits, !inv);
    } else if (t.released) {
      b.set(t.at, inv);  // the line falls back to space: to a receiver, a start bit
    } else {
      b.set(t.at, !inv);
      b.set(t.span->spike_at, inv);
      b.set(t.span->spike_at + t.span->spike, !inv);
    }
  }
  return b.take();
}

// One DE channel per talker, high while its driver is enabled.
void driver_channels(const LogicLayout& l, double rate, std::vector<ChannelSignal>& out) {
  std::map<int, std::vector<const DriverWindow*>> by_talker;
  for (const DriverWindow& w : l.drivers) by_talker[w.talker].push_back(&w);
  SimRandom none(0);
  for (const auto& [talker, windows] : by_talker) {
    SignalBuilder b(talker == 0 ? "DE_M" : "DE_" + std::to_string(talker), false, rate, 0, none);
    for (const DriverWindow* w : windows) {
      b.set(w->on, true);
      b.set(w->off, false);
    }
    out.push_back(b.take());
  }
}

}  // namespace

LogicSignals logic_signals(const LogicLayout& layout, const LogicOptions& o, std::uint64_t seed) {
  LogicSignals s;
  s.sample_rate = o.sample_rate;
  s.samples = static_cast<std::uint64_t>(std::llround(layout.end * o.sample_rate / 1e6));
  s.start_unix = layout.origin / 1'000'000;
  SimRandom random(seed ^ 0x7177E5ull);
  if (o.bus) s.channels.push_back(uart_channel("A-B", layout, o, true, true, true, random));
  if (o.tx) s.channels.push_back(uart_channel("TX", layout, o, true, false, false, random));
  if (o.rx) s.channels.push_back(uart_channel("RX", layout, o, false, true, false, random));
  if (o.de) driver_channels(layout, o.sample_rate, s.channels);
  return s;
}

}  // namespace pvtap::sim
