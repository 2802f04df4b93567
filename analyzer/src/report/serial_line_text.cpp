// A logic-analyzer bus's serial line in the text report.
#include <cmath>

#include "report/report_line.h"
#include "report/serial_line_report.h"

namespace pvtap::analyzer {

void append_serial_line_text(const SerialLineReport& s, std::string& o) {
  const char parity = s.parity == "even" ? 'E' : s.parity == "odd" ? 'O' : 'N';
  o += report_line("serial line on channel %s: %u baud %u%c%u%s, %s (measured %.0f baud, %+.2f %%)",
                   s.channel.c_str(), s.baud, s.data_bits, parity, s.stop_bits,
                   s.inverted ? " inverted" : "", s.detected ? "found from the samples" : "given",
                   s.measured_baud, s.deviation * 100);
  // Over 2 % the rate is no standard one: worth a look at the device's clock or settings.
  if (std::abs(s.deviation) > 0.02) {
    o += report_line("  the rate is %.1f %% off the nearest standard rate", s.deviation * 100);
  }
  o += report_line("  line errors: framing %llu, parity %llu, break %llu; driver glitches %llu",
                   static_cast<unsigned long long>(s.framing_errors),
                   static_cast<unsigned long long>(s.parity_errors),
                   static_cast<unsigned long long>(s.breaks),
                   static_cast<unsigned long long>(s.driver_glitches));
}

}  // namespace pvtap::analyzer
