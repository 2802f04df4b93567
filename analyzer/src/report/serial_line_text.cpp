// A logic-analyzer bus's serial line in the text report.
#include "report/report_line.h"
#include "report/serial_line_report.h"

namespace pvtap::analyzer {
namespace {

// A driver released before the last stop bit ended cut that byte short: a finding.
void append_turnaround_text(const DriverTurnaround& t, std::string& o) {
  o += report_line(
      "  driver %s, station %u: released %.1f us after the last stop bit "
      "(%.1f to %.1f us, %llu frames)",
      t.driver.c_str(), unsigned{t.station}, t.mean_us, t.min_us, t.max_us,
      static_cast<unsigned long long>(t.frames));
  if (t.truncated > 0) {
    o += report_line(
        "  driver %s, station %u: released before the last stop bit ended in %llu "
        "frames: a truncated last byte",
        t.driver.c_str(), unsigned{t.station}, static_cast<unsigned long long>(t.truncated));
  }
}

}  // namespace

void append_serial_line_text(const SerialLineReport& s, std::string& o) {
  const char parity = s.parity == "even" ? 'E' : s.parity == "odd" ? 'O' : 'N';
  if (!s.measured) {
    o += report_line("serial line on %s: %u baud %u%c%u, %s", s.channel.c_str(), s.baud,
                     s.data_bits, parity, s.stop_bits, s.how_found.c_str());
    return;
  }
  o += report_line("serial line on channel %s: %u baud %u%c%u%s, %s (measured %.0f baud, %+.2f %%)",
                   s.channel.c_str(), s.baud, s.data_bits, parity, s.stop_bits,
                   s.inverted ? " inverted" : "", s.detected ? s.how_found.c_str() : "given",
                   s.measured_baud, s.deviation * 100);
  // Over 2 % the rate is no standard one: worth a look at the device's clock or settings.
  if (s.clock_deviations > 0) {
    o += report_line("  clock deviation: the rate is %.1f %% off the nearest standard rate",
                     s.deviation * 100);
  }
  o += report_line("  line errors: framing %llu, parity %llu, break %llu; driver glitches %llu",
                   static_cast<unsigned long long>(s.framing_errors),
                   static_cast<unsigned long long>(s.parity_errors),
                   static_cast<unsigned long long>(s.breaks),
                   static_cast<unsigned long long>(s.driver_glitches));
  for (const DriverTurnaround& t : s.turnarounds) append_turnaround_text(t, o);
}

}  // namespace pvtap::analyzer
