#include "report/glossary.h"

#include <array>

namespace pvtap::analyzer {
namespace {

// Kept to one line each: they are tooltips in the HTML page and rows of `pvtap glossary`.
constexpr std::array kTerms = {
    GlossaryTerm{"bus", "buses[].bus",
                 "one RS485 line as one tap heard it, named by its device, channels, gateway "
                 "endpoint or logger serial (a capture of serial records: serial)"},
    GlossaryTerm{"station", "stations",
                 "a slave address that answered or was asked with a good check"},
    GlossaryTerm{"bus bytes", "bytes",
                 "every byte heard on the bus, in frames or as noise (bytes lost in gaps are "
                 "counted beside)"},
    GlossaryTerm{"frame", "frames",
                 "a whole request or reply as its dialect frames it, with its check verdict"},
    GlossaryTerm{"request", "requests", "a frame from the master (the data logger) to a station"},
    GlossaryTerm{"response", "responses", "a frame from a station, answering a request"},
    GlossaryTerm{"bad check", "bad_checks",
                 "a frame whose CRC or checksum does not hold: the line damaged it"},
    GlossaryTerm{"damaged reply", "damaged_replies",
                 "a reply with a bad check: the slave answered and the line damaged the answer, "
                 "so its request is no timeout"},
    GlossaryTerm{"damaged request left unanswered", "unanswered_damaged_requests",
                 "a request with a bad check that no station answered: the slave rightly "
                 "ignored it"},
    GlossaryTerm{"timeout", "timeouts",
                 "a good request its station did not answer within --timeout"},
    GlossaryTerm{"exception", "exceptions",
                 "a reply in which the station refuses the request: a Modbus exception code or "
                 "a Hybrid error reply (0xFF)"},
    GlossaryTerm{"malformed frame", "malformed_frames",
                 "a frame whose check holds but whose layout breaks its function's rules"},
    GlossaryTerm{"unsolicited reply", "unsolicited", "a reply that no waiting request asked for"},
    GlossaryTerm{"late reply", "late_replies",
                 "a reply that came after its request had already timed out"},
    GlossaryTerm{"duplicate reply", "duplicates",
                 "a second reply to one request, the same bytes again"},
    GlossaryTerm{"address conflict", "address_conflicts",
                 "a second reply to one request with other contents: two devices answer to one "
                 "address"},
    GlossaryTerm{"echo", "echoes",
                 "a request seen twice, back to back and byte for byte: the tap's own adapter "
                 "repeating what its master sent; counted once, as one request"},
    GlossaryTerm{"collision", "collisions",
                 "two transmissions at once on a bus of more than one master: bytes that belong "
                 "to no frame, or two requests overlapping"},
    GlossaryTerm{"lost in a collision", "lost_in_collision",
                 "a request whose reply was due while a collision happened (counted among the "
                 "timeouts)"},
    GlossaryTerm{"byte count mismatch", "byte_count_mismatches",
                 "a frame whose byte count disagrees with its request or with the quantity it "
                 "carries"},
    GlossaryTerm{"unanswered at end", "unanswered_at_end",
                 "a request still waiting for its reply when the input ended: not judged"},
    GlossaryTerm{"unknown station", "unknown_station",
                 "damaged frames whose station byte cannot be trusted, counted with the "
                 "address they claimed"},
    GlossaryTerm{"noise", "noise_bytes",
                 "bus bytes in no frame (line noise, fragments of frames), counted in runs"},
    GlossaryTerm{"gap", "gaps",
                 "a place where the capture lost bytes (a TCP hole, a dropped record), "
                 "declared with how many bytes when known, never guessed"},
    GlossaryTerm{"latency", "latency_ms",
                 "from a request's last byte to its reply's first, in ms (through a gateway: "
                 "between their TCP segments)"},
    GlossaryTerm{"p50", "latency_ms.p50", "the median: half of the values are at or below it"},
    GlossaryTerm{"p95", "latency_ms.p95", "95 % of the values are at or below it"},
    GlossaryTerm{"mean", "latency_ms.mean", "the sum of the values divided by their count"},
    GlossaryTerm{"master", "buses[].masters",
                 "a device that sends requests (a data logger, a meter reader), told apart from "
                 "another by its own poll cycle: its plan, period, share and turnaround"},
    GlossaryTerm{"poll period", "buses[].polls[].period_ms",
                 "the time between two requests of the same kind to the same station, in ms"},
    GlossaryTerm{"jitter", "buses[].polls[].jitter_ms",
                 "how much a poll period varies: the standard deviation of its intervals, in ms"},
    GlossaryTerm{"t1.5", "buses[].timing.t15_violations",
                 "Modbus RTU: a silence over 1.5 characters inside a frame breaks the frame"},
    GlossaryTerm{"t3.5", "buses[].timing.t35_violations",
                 "Modbus RTU: frames must be apart by a silence of at least 3.5 characters"},
    GlossaryTerm{"none measured", "",
                 "a statistic over nothing: no value was measured, so none is shown (never 0)"},
};

}  // namespace

std::span<const GlossaryTerm> glossary() {
  return kTerms;
}

const GlossaryTerm* glossary_term(std::string_view term) {
  for (const GlossaryTerm& t : kTerms) {
    if (t.term == term) return &t;
  }
  return nullptr;
}

const GlossaryTerm* glossary_term_of_key(std::string_view json_key) {
  for (const GlossaryTerm& t : kTerms) {
    if (t.json_key == json_key) return &t;
  }
  return nullptr;
}

std::string_view meaning_of(std::string_view term) {
  const GlossaryTerm* t = glossary_term(term);
  return t == nullptr ? std::string_view() : t->meaning;
}

}  // namespace pvtap::analyzer
