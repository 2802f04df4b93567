#include "plant/register_image.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pvtap::sim {

RegisterImage::RegisterImage(Dialect dialect)
    : dialect_(dialect), map_(&builtin_register_map(dialect)) {}

const RegisterDef& RegisterImage::def(std::string_view key) const {
  const RegisterDef* d = map_->find_key(key);
  // A missing key is a simulator bug: the plant model names registers of the core's map.
  if (d == nullptr) throw std::logic_error("register map has no key " + std::string(key));
  return *d;
}

void RegisterImage::put_words(const RegisterDef& d, std::uint32_t raw) {
  const unsigned step = address_step(dialect_);
  if (d.words == 1) {
    words_[d.address] = static_cast<std::uint16_t>(raw);
    return;
  }
  // Two-word numbers go high word first; the decimal rule keeps the low part under 10000.
  const bool decimal = d.pair_rule == PairRule::Decimal;
  const auto high = static_cast<std::uint16_t>(decimal ? raw / 10000 : raw >> 16);
  const auto low = static_cast<std::uint16_t>(decimal ? raw % 10000 : raw & 0xFFFF);
  words_[d.address] = high;
  words_[static_cast<std::uint16_t>(d.address + step)] = low;
}

void RegisterImage::set_value(std::string_view key, double value) {
  const RegisterDef& d = def(key);
  const auto raw = static_cast<std::int64_t>(std::llround(value / d.scale));
  put_words(d, static_cast<std::uint32_t>(raw));
}

void RegisterImage::set_raw(std::string_view key, std::uint32_t raw) {
  put_words(def(key), raw);
}

void RegisterImage::set_text(std::string_view key, std::string_view text) {
  const RegisterDef& d = def(key);
  const unsigned step = address_step(dialect_);
  for (std::uint16_t w = 0; w < d.words; ++w) {
    const auto at = static_cast<std::size_t>(w) * 2;
    const auto hi = static_cast<std::uint8_t>(at < text.size() ? text[at] : ' ');
    const auto lo = static_cast<std::uint8_t>(at + 1 < text.size() ? text[at + 1] : ' ');
    words_[static_cast<std::uint16_t>(d.address + w * step)] =
        static_cast<std::uint16_t>(hi << 8 | lo);
  }
}

std::uint16_t RegisterImage::word_at(std::uint16_t address) const {
  const auto it = words_.find(address);
  return it == words_.end() ? 0 : it->second;
}

WordList RegisterImage::block(std::uint16_t start, std::uint16_t count) const {
  WordList out;
  const unsigned step = address_step(dialect_);
  for (unsigned i = 0; i < count; ++i)
    out.push_back(word_at(static_cast<std::uint16_t>(start + i * step)));
  return out;
}

std::string RegisterImage::text_of(const RegisterDef& d) const {
  std::string text;
  const unsigned step = address_step(dialect_);
  for (std::uint16_t w = 0; w < d.words; ++w) {
    const std::uint16_t word = word_at(static_cast<std::uint16_t>(d.address + w * step));
    for (const auto c : {word >> 8, word & 0xFF})
      text += (c >= 0x20 && c < 0x7F && c != '"' && c != '\\') ? static_cast<char>(c) : '?';
  }
  return text;
}

std::vector<RegisterTruth> RegisterImage::truth(std::uint16_t start, std::uint16_t count) const {
  std::vector<RegisterTruth> out;
  const unsigned step = address_step(dialect_);
  const unsigned end = start + count * step;
  for (const RegisterDef& d : map_->registers()) {
    if (d.is_range() || d.address < start || d.address + d.words * step > end) continue;
    std::uint32_t raw = word_at(d.address);
    if (d.words == 2) {
      const std::uint32_t low = word_at(static_cast<std::uint16_t>(d.address + step));
      raw = d.pair_rule == PairRule::Decimal ? raw * 10000 + low : raw << 16 | low;
    }
    RegisterTruth t;
    t.address = std::string(format_register_address(dialect_, d.address).view());
    t.key = std::string(d.key);
    t.raw = raw;
    t.numeric = d.kind == RegisterKind::Number;
    if (d.kind == RegisterKind::Text) t.text = text_of(d);
    double base = raw;
    if (d.is_signed)
      base = d.words == 1 ? static_cast<std::int16_t>(raw) : static_cast<std::int32_t>(raw);
    t.value = base * d.scale;
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace pvtap::sim
