// AutoBaud: reads unmarked, fed to the search, and held until it settles.
#include "serial/auto_baud.h"

#include <optional>

namespace pvtap::analyzer {
namespace {

char parity_letter(Parity p) {
  return p == Parity::Even ? 'E' : p == Parity::Odd ? 'O' : 'N';
}

std::string text_of(const LineSetting& s) {
  return std::to_string(s.baud) + " " + format_name(s.format);
}

}  // namespace

SerialLine AutoBaud::line() const {
  const UartFormat& f = search_.setting().format;
  return SerialLine{parity_letter(f.parity), static_cast<int>(f.stop_bits)};
}

std::string AutoBaud::setting_text() const {
  return text_of(search_.setting());
}

std::string AutoBaud::status_text() const {
  return settled() ? setting_text() + " found" : "searching: " + setting_text();
}

AutoBaud::Outcome AutoBaud::judge(bool was_settled, bool changed) {
  Outcome o;
  o.change = changed;
  o.lost = was_settled && changed;
  o.settled = !was_settled && search_.settled();
  if (o.settled) {
    ever_settled_ = true;
    found_ = search_.setting();
  }
  return o;
}

AutoBaud::Outcome AutoBaud::take(std::span<const std::uint8_t> read, double time,
                                 BusBytes& for_bus) {
  bytes_.clear();
  marks_.unmark(read, bytes_);
  const bool was_settled = search_.settled();
  const bool changed = search_.feed(bytes_, time);
  const Outcome o = judge(was_settled, changed);
  for_bus.clear();
  if (changed && !was_settled) {
    held_.clear();  // read at a setting that is given up; a mark cut by the read goes too
    marks_ = MarkedBytes{};
    return o;
  }
  // Read at the setting found: the bus reads them even when they end the setting.
  BusBytes& to = was_settled ? for_bus : held_;
  for (const LineByte& b : bytes_) to.bytes.push_back(b.value);
  if (!bytes_.empty()) to.reads.emplace_back(to.bytes.size(), time);
  if (o.settled) std::swap(for_bus, held_);
  return o;
}

AutoBaud::Outcome AutoBaud::tick(double time) {
  const bool was_settled = search_.settled();
  const Outcome o = judge(was_settled, search_.tick(time));
  if (o.change) {
    held_.clear();
    marks_ = MarkedBytes{};
  }
  return o;
}

std::optional<SerialLineReport> AutoBaud::report(const std::string& path) const {
  if (!ever_settled_) return std::nullopt;
  SerialLineReport r;
  r.baud = found_.baud;
  r.measured_baud = found_.baud;
  r.measured = false;
  r.parity = parity_name(found_.format.parity);
  r.data_bits = found_.format.data_bits;
  r.stop_bits = found_.format.stop_bits;
  r.detected = true;
  r.how_found = "found from the traffic";
  r.channel = path;
  r.has_line_errors = false;
  return r;
}

}  // namespace pvtap::analyzer
