// Collects field and expert registrations that are built at run time, then registers them.
#pragma once

#include <epan/expert.h>
#include <epan/proto.h>

#include <cstdint>
#include <string>
#include <vector>

#include "plan/field_table.h"

namespace pvtap::dissector {

// FieldList: hf_register_info records with run-time names. Wireshark keeps pointers into the
// registered array and its strings, so both are copied to storage that is never freed.
class FieldList {
 public:
  void add(int* id, const std::string& name, const std::string& abbrev, ftenum type, int display,
           const void* strings = nullptr, std::uint64_t bitmask = 0, const std::string& blurb = {});
  void register_all(int proto);

 private:
  std::vector<hf_register_info> records_;
};

// ExpertList: ei_register_info records with run-time names, kept the same way.
class ExpertList {
 public:
  void add(expert_field* id, const std::string& name, int group, int severity,
           const std::string& summary);
  void register_all(int proto);

 private:
  std::vector<ei_register_info> records_;
};

// ExpertRowOf: a line of an expert table (plan/field_table.h, and a carrier's own), whose ids
// are of the enum `Id`.
template <class Id>
struct ExpertRowOf {
  Id id;
  const char* abbrev;
  int group;
  int severity;
  const char* summary;
};
using ExpertRow = ExpertRowOf<TreeExpert>;

#define PVTAP_EXPERT_ROW(id, abbrev, group, severity, summary) \
  {TreeExpert::id, abbrev, group, severity, summary},

}  // namespace pvtap::dissector
