#include "sources/capture_order.h"

#include <algorithm>
#include <span>

#include "formatting/number_text.h"
#include "pvtap/pcap/capture_file.h"
#include "pvtap/pcap/link_types.h"

namespace pvtap::analyzer {
namespace {

PlannedCapture probe(const std::string& path) {
  PlannedCapture planned;
  planned.path = path;
  CaptureFile file;
  if (!file.open(path)) {
    planned.error = file.error();
    return planned;
  }
  planned.link_type = file.link_type();
  if (!input_kind_of(file.link_type())) {
    planned.error = "unsupported link type " + file.link_type_name() +
                    "; supported: " + supported_link_types_text();
    return planned;
  }
  CapturedPacket packet;
  if (file.next(packet) == CaptureFile::Next::Packet) {
    planned.first_time = packet.time;
    planned.first_record.assign(packet.bytes.begin(), packet.bytes.end());
  }
  return planned;
}

bool same_first_record(const PlannedCapture& a, const PlannedCapture& b) {
  return a.first_time && b.first_time && *a.first_time == *b.first_time &&
         a.first_record == b.first_record;
}

// Files in time order; a repeat begins with the same record as a file beside it.
std::optional<std::string> find_repeat(const std::vector<PlannedCapture>& ordered) {
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    for (std::size_t j = i + 1; j < ordered.size(); ++j) {
      if (ordered[j].first_time != ordered[i].first_time) break;
      if (same_first_record(ordered[i], ordered[j])) {
        return repeated_records_text(ordered[i].path, ordered[j].path, *ordered[i].first_time);
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::string repeated_records_text(const std::string& a, const std::string& b, double time) {
  std::string when;
  append_utc_date_time(when, time);
  return a + " and " + b + " hold the same records (both have the one of " + when +
         " UTC): give each record once";
}

CapturePlan plan_captures(const std::vector<std::string>& paths, bool duplex) {
  CapturePlan plan;
  for (const std::string& path : paths) {
    PlannedCapture planned = probe(path);
    if (duplex) {
      planned.direction = &path == &paths.front() ? Direction::ToSlave : Direction::FromSlave;
    }
    (planned.error.empty() ? plan.readable : plan.unreadable).push_back(std::move(planned));
  }
  // Stable: files whose first records share a time keep the order given.
  std::stable_sort(plan.readable.begin(), plan.readable.end(),
                   [](const PlannedCapture& a, const PlannedCapture& b) {
                     if (!b.first_time) return a.first_time.has_value();
                     return a.first_time && *a.first_time < *b.first_time;
                   });
  plan.refusal = find_repeat(plan.readable);
  return plan;
}

}  // namespace pvtap::analyzer
