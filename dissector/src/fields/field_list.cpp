#include "fields/field_list.h"

#include <algorithm>

namespace pvtap::dissector {
namespace {

const char* persist(const std::string& text) {
  return text.empty() ? nullptr : g_strdup(text.c_str());
}

template <typename T>
T* persist(const std::vector<T>& records) {
  auto* out = g_new(T, records.size());
  std::copy(records.begin(), records.end(), out);
  return out;
}

}  // namespace

void FieldList::add(int* id, const std::string& name, const std::string& abbrev, ftenum type,
                    int display, const void* strings, std::uint64_t bitmask,
                    const std::string& blurb) {
  hf_register_info hf = {
      id, {persist(name), persist(abbrev), type, display, strings, bitmask, persist(blurb), HFILL}};
  records_.push_back(hf);
}

void FieldList::register_all(int proto) {
  if (records_.empty()) return;
  proto_register_field_array(proto, persist(records_), static_cast<int>(records_.size()));
}

void ExpertList::add(expert_field* id, const std::string& name, int group, int severity,
                     const std::string& summary) {
  ei_register_info ei = {id, {persist(name), group, severity, persist(summary), EXPFILL}};
  records_.push_back(ei);
}

void ExpertList::register_all(int proto) {
  if (records_.empty()) return;
  expert_module_t* module = expert_register_protocol(proto);
  expert_register_field_array(module, persist(records_), static_cast<int>(records_.size()));
}

}  // namespace pvtap::dissector
