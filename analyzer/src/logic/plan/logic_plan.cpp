// plan_logic_audit: probe the recording, keep the channels that talk, refuse what cannot be
// read well.
#include "logic/plan/logic_plan.h"

#include "logic/plan/channel_pairing.h"
#include "pvtap/pcap/file_format.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace pvtap::analyzer {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string channel_list(const std::vector<LogicChannel>& channels) {
  std::string out;
  for (const LogicChannel& c : channels) out += (out.empty() ? "" : ", ") + c.name;
  return out.empty() ? "none" : out;
}

// Too few samples per bit to read a UART: the reason, naming the channel and its rate.
std::string too_slow(const ProbedChannel& p, double sample_rate) {
  char text[200];
  std::snprintf(text, sizeof text,
                "channel %s: %.0f baud at %.0f samples/s is %.1f samples per bit; at least %.0f "
                "are needed",
                p.channel.name.c_str(), p.line->baud.measured, sample_rate,
                p.line->samples_per_bit(), kMinSamplesPerBit);
  return text;
}

// Without --channels, a channel whose frames never check beside one whose frames do is no bus:
// a driver-enable line's pulses read as slow characters, never as frames.
void drop_frameless(std::vector<ProbedChannel>& channels) {
  const auto frameless = [](const ProbedChannel& p) { return p.line->trial.good_frames == 0; };
  if (!std::all_of(channels.begin(), channels.end(), frameless)) std::erase_if(channels, frameless);
}

// The channels asked for must all talk; without --channels, those that do are kept.
std::string keep_talking(LogicPlan& plan, const std::vector<ProbedChannel>& probed, bool asked) {
  for (const ProbedChannel& p : probed) {
    const bool talks = p.line && p.line->has_traffic;
    if (p.line && p.line->samples_per_bit() < kMinSamplesPerBit && (talks || asked)) {
      return too_slow(p, plan.sample_rate);
    }
    if (talks) {
      plan.channels.push_back(p);
    } else if (asked) {
      return "channel " + p.channel.name + " carries no UART traffic";
    }
  }
  if (!asked) drop_frameless(plan.channels);
  return plan.channels.empty() ? "no channel carries UART traffic" : "";
}

// --de: each named channel found, and none of them read as a UART.
std::string find_drivers(LogicPlan& plan, const LineProbe& probe,
                         const std::vector<std::string>& drivers,
                         std::vector<ProbedChannel>& probed) {
  for (const std::string& name : drivers) {
    const auto& all = probe.available();
    const auto found =
        std::find_if(all.begin(), all.end(), [&](const LogicChannel& c) { return c.name == name; });
    if (found == all.end())
      return "no channel " + name + " (the recording has: " + channel_list(all) + ")";
    plan.drivers.push_back(*found);
    std::erase_if(probed, [&](const ProbedChannel& p) { return p.channel.name == name; });
  }
  return {};
}

// --channels "A" or "A,B": the groups of names, or why they are no buses.
std::string read_groups(const std::vector<std::string>& given,
                        std::vector<std::vector<std::string>>& groups,
                        std::vector<std::string>& names) {
  for (const std::string& text : given) {
    std::vector<std::string> group;
    std::size_t from = 0;
    while (from <= text.size()) {
      const std::size_t comma = std::min(text.find(',', from), text.size());
      group.push_back(text.substr(from, comma - from));
      from = comma + 1;
    }
    if (group.size() > 2 || std::find(group.begin(), group.end(), "") != group.end())
      return "--channels " + text +
             ": one channel, or the two directions of one bus (REQUESTS,REPLIES)";
    for (const std::string& n : group) {
      if (std::find(names.begin(), names.end(), n) != names.end())
        return "--channels: channel " + n + " is named twice";
      names.push_back(n);
    }
    groups.push_back(std::move(group));
  }
  return {};
}

// Each group's channels by their place in the plan; without groups, each channel a bus.
void form_buses(LogicPlan& plan, const std::vector<std::vector<std::string>>& groups) {
  if (groups.empty()) {
    plan.buses = pair_channels(plan.channels);
    return;
  }
  for (const auto& group : groups) {
    std::vector<std::size_t> bus;
    for (const std::string& name : group)
      for (std::size_t i = 0; i < plan.channels.size(); ++i)
        if (plan.channels[i].channel.name == name) bus.push_back(i);
    plan.buses.push_back(std::move(bus));
  }
}

}  // namespace

bool is_logic_recording(const std::string& path) {
  // The content decides; the name only where the content says nothing (text that is no VCD,
  // a file that cannot be read, whose error then comes from the reader the name points to).
  switch (file_format_of(path)) {
    case FileFormat::Zip:
    case FileFormat::Vcd:
      return true;
    case FileFormat::Pcap:
    case FileFormat::Pcapng:
      return false;
    case FileFormat::Text:
    case FileFormat::Unknown:
    case FileFormat::Unreadable:
      break;
  }
  return ends_with(path, ".sr") || ends_with(path, ".vcd") || ends_with(path, ".csv");
}

LogicPlan plan_logic_audit(const std::string& path, const std::vector<std::string>& buses,
                           const std::vector<std::string>& drivers, double sample_rate) {
  LogicPlan plan;
  plan.path = path;
  std::vector<std::vector<std::string>> groups;
  std::vector<std::string> names;
  if (const std::string why = read_groups(buses, groups, names); !why.empty()) {
    plan.error = why;
    return plan;
  }
  // The file's own trouble (missing, a directory, no permission) in the system's words,
  // before libsigrok would call it "not a recording".
  std::error_code ec;
  const bool regular = std::filesystem::is_regular_file(path, ec);
  if (ec || !regular) {
    plan.error = path + ": " + (ec ? ec.message() : std::string("not a regular file"));
    return plan;
  }
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    std::fclose(f);
  } else {
    plan.error = path + ": " + std::strerror(errno);
    return plan;
  }
  LineProbe probe(names);
  SampleHold hold(probe, kHeldRecordingLimit);
  const std::string error = read_logic_file(path, hold, sample_rate);
  probe.finish();
  if (error.empty()) plan.held = hold.take();
  plan.sample_rate = probe.sample_rate();
  std::vector<ProbedChannel> probed = probe.channels();
  if (!error.empty()) {
    plan.error = path + ": " + error;
  } else if (!probe.missing().empty()) {
    plan.error = path + ": no channel " + probe.missing().front() +
                 " (the recording has: " + channel_list(probe.available()) + ")";
  } else if (plan.sample_rate <= 0) {
    plan.error = path + ": the recording does not give its sample rate (give --samplerate)";
  } else if (const std::string missing = find_drivers(plan, probe, drivers, probed);
             !missing.empty()) {
    plan.error = path + ": " + missing;
  } else if (const std::string why = keep_talking(plan, probed, !names.empty()); !why.empty()) {
    plan.error = path + ": " + why;
  } else {
    form_buses(plan, groups);
  }
  return plan;
}

void keep_probed(const LineProbe& probe, bool asked, LogicPlan& plan) {
  if (const std::string why = keep_talking(plan, probe.channels(), asked); !why.empty()) {
    plan.error = plan.path + ": " + why;
    return;
  }
  form_buses(plan, {});
}

}  // namespace pvtap::analyzer
