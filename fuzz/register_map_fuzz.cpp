// Fuzz target register_map: the register map loader on arbitrary TOML text. Every problem must
// come back as a diagnostic (never a crash or an escaping exception); a map that loads must be
// sorted, findable by its keys and addresses, and decode words without trouble.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_input.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_map.h"

namespace {

void check_loaded(const pvtap::RegisterMap& map) {
  const auto regs = map.registers();
  for (std::size_t i = 0; i < regs.size(); ++i) {
    PVTAP_FUZZ_CHECK(i == 0 || regs[i - 1].address <= regs[i].address);
    PVTAP_FUZZ_CHECK(map.find_key(regs[i].key) != nullptr);
    PVTAP_FUZZ_CHECK(map.locate(regs[i].address).has_value());
    PVTAP_FUZZ_CHECK(regs[i].words >= 1 && regs[i].repeat >= 1);
  }
}

void decode_with(const pvtap::RegisterMap& map) {
  pvtap::RegisterDecoder decoder;
  decoder.use_map(map);
  std::vector<std::uint16_t> words(64);
  for (std::size_t i = 0; i < words.size(); ++i) {
    words[i] = static_cast<std::uint16_t>(i * 0x1357u);
  }
  std::vector<pvtap::DecodedValue> out;
  for (const auto& def : map.registers()) {
    (void)decoder.decode_block(map.dialect(), def.address, words, pvtap::ValueOrigin::ReadReply,
                               out);
    if (out.size() > 4096) out.clear();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto loaded = pvtap::load_register_map(text, "fuzz.toml");
  if (!loaded) {
    PVTAP_FUZZ_CHECK(!loaded.diagnostics().empty());
    for (const auto& e : loaded.diagnostics()) PVTAP_FUZZ_CHECK(!e.message.empty());
    (void)loaded.error_text();
    return 0;
  }
  check_loaded(loaded.value());
  const auto resolved = pvtap::resolve_user_register_map(loaded.value());
  if (resolved) {
    check_loaded(resolved.value());
    decode_with(resolved.value());
  }
  return 0;
}
