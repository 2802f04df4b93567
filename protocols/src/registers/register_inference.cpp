#include "pvtap/registers/register_inference.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>

#include "registers/inference_evidence.h"

namespace pvtap {
namespace {

using detail::hint_for;
using detail::words_of;

constexpr std::size_t kHigh = 0, kLow = 1;  // PairStats::order, by WordOrder

// The plausible range of a float32 reading: finite, and 0 or 1e-3 <= |x| <= 1e6.
bool plausible(float f) {
  const float a = std::fabs(f);
  return std::isfinite(f) && (a == 0.0f || (a >= 1e-3f && a <= 1e6f));
}

bool printable(unsigned c) {
  return c == 0 || (c >= 0x20 && c < 0x7F);
}

std::uint32_t join(std::uint16_t high, std::uint16_t low) {
  return std::uint32_t{high} << 16 | low;
}

const char* order_words(std::size_t o) {
  return o == kHigh ? "high word first" : "low word first";
}

}  // namespace

std::string_view to_string(InferredKind kind) {
  switch (kind) {
    case InferredKind::U16:
      return "u16";
    case InferredKind::S16:
      return "s16";
    case InferredKind::U32:
      return "u32";
    case InferredKind::S32:
      return "s32";
    case InferredKind::Float32:
      return "float32";
    case InferredKind::Text:
      return "text";
    case InferredKind::Bits:
      return "bits";
    case InferredKind::Unused:
      return "unused";
  }
  return "?";
}

BlockInference::BlockInference(std::size_t words)
    : words_(words), pairs_(words > 0 ? words - 1 : 0), latest_(words) {}

void BlockInference::pair_sample(std::size_t i, std::uint16_t a, std::uint16_t b) {
  PairStats& p = pairs_[i];
  const std::uint16_t pa = words_[i].last, pb = words_[i + 1].last;
  const bool before = samples_ > 0;
  if (before && (a != pa || b != pb)) ++p.changes;
  for (std::size_t o = 0; o < 2; ++o) {
    PairOrder& s = p.order[o];
    const std::uint16_t hi = o == kHigh ? a : b, lo = o == kHigh ? b : a;
    const std::uint16_t phi = o == kHigh ? pa : pb, plo = o == kHigh ? pb : pa;
    const std::uint32_t bits = join(hi, lo), previous = join(phi, plo);
    const float f = std::bit_cast<float>(bits);
    if (!std::isfinite(f)) {
      ++s.not_finite;
    } else {
      if (plausible(f)) ++s.plausible;
      const bool first = s.plausible + s.not_finite == 1 && plausible(f);
      s.fmin = first ? f : std::min(s.fmin, f);
      s.fmax = first ? f : std::max(s.fmax, f);
    }
    const auto i32 = static_cast<std::int32_t>(bits);
    s.umin = std::min(s.umin, bits);
    s.umax = std::max(s.umax, bits);
    s.imin = std::min(s.imin, i32);
    s.imax = std::max(s.imax, i32);
    if (hi == ((lo & 0x8000u) != 0 ? 0xFFFFu : 0u)) ++s.extension;
    if (!before || bits == previous) continue;
    const float pf = std::bit_cast<float>(previous);
    if (std::isfinite(f) && std::isfinite(pf) &&
        std::fabs(f - pf) <= 0.1f * std::max(std::fabs(f), std::fabs(pf))) {
      ++s.smooth;
    }
    if (bits < previous) ++s.u32_downs;
    if (lo<plo&& unsigned{plo} - unsigned{lo}> 0x8000u && hi == static_cast<std::uint16_t>(phi + 1))
      ++s.carries;
  }
}

void BlockInference::add(std::span<const std::uint16_t> words) {
  if (words.size() != words_.size()) return;
  for (std::size_t i = 0; i + 1 < words.size(); ++i) pair_sample(i, words[i], words[i + 1]);
  for (std::size_t i = 0; i < words.size(); ++i) {
    WordStats& s = words_[i];
    const std::uint16_t w = words[i];
    if (samples_ == 0) {
      s.first = w;
    } else if (w != s.last) {
      ++s.changes;
      s.changed_bits = static_cast<std::uint16_t>(s.changed_bits | (w ^ s.last));
      if (w > s.last) {
        ++s.ups;
      } else {
        ++s.downs;
        if (unsigned{s.last} - w > 0x8000u) ++s.wraps;
      }
      s.step_unsigned += static_cast<std::uint64_t>(std::abs(int{w} - int{s.last}));
      s.step_signed += static_cast<std::uint64_t>(
          std::abs(int{static_cast<std::int16_t>(w)} - int{static_cast<std::int16_t>(s.last)}));
    }
    s.min = std::min(s.min, w);
    s.max = std::max(s.max, w);
    s.smin = std::min(s.smin, static_cast<std::int16_t>(w));
    s.smax = std::max(s.smax, static_cast<std::int16_t>(w));
    if (w == 0xFFFF || w == 0x8000) ++s.fill;
    if (w == 0) {
      ++s.nul;
    } else if (printable(w >> 8u) && printable(w & 0xFFu)) {
      ++s.printable;
    }
    s.last = w;
    latest_[i] = w;
  }
  ++samples_;
}

// A run of words that hold ASCII text in every value: printable characters, then NUL padding
// (a NUL followed by a character starts the next text). At least 4 characters in 2 words, and
// text that hardly changes.
std::size_t BlockInference::text_run(std::size_t i, std::size_t end, InferredValue& out) const {
  const std::uint32_t n = samples_;
  const auto text_word = [&](std::size_t k) {
    return words_[k].printable == n && words_[k].changes * 4 <= n;
  };
  const auto padding = [&](std::size_t k) { return words_[k].nul == n; };
  if (!text_word(i)) return 0;
  std::size_t j = i;
  // A map's text entry holds at most 16 words: a longer text is read as several.
  end = std::min(end, i + 16);
  while (j < end && text_word(j)) {
    ++j;
    if ((words_[j - 1].last & 0xFFu) == 0) break;  // its last character is a NUL: the end
  }
  while (j < end && padding(j)) ++j;
  const std::size_t count = j - i;
  std::string text;
  for (std::size_t k = i; k < j; ++k) {
    for (const unsigned c : {unsigned{latest_[k]} >> 8u, latest_[k] & 0xFFu}) {
      if (c == 0) break;
      text += static_cast<char>(c);
    }
    if ((latest_[k] & 0xFFu) == 0 || (latest_[k] >> 8u) == 0) break;
  }
  if (count < 2 || text.size() < 4) return 0;
  std::uint32_t changes = 0;
  for (std::size_t k = i; k < j; ++k) changes += words_[k].changes;
  out = InferredValue{};
  out.offset = static_cast<std::uint16_t>(i);
  out.words = static_cast<std::uint16_t>(count);
  out.kind = InferredKind::Text;
  out.constant = changes == 0;
  out.samples = n;
  out.text = text;
  out.confidence = text.size() >= 8 ? 0.9 : 0.7;
  out.evidence = words_of("text: %zu characters in %zu words, printable ASCII in all %u values%s",
                          text.size(), count, n, changes == 0 ? ", never changed" : "");
  return count;
}

// Two words that read as one integer: a counter whose low word carries into its high word, a
// signed value whose other word is only its sign, or a counter whose high word is small and
// steady while its low word grows.
bool BlockInference::pair(std::size_t i, InferredValue& out) const {
  const std::uint32_t n = samples_;
  const PairStats& p = pairs_[i];
  out = InferredValue{};
  out.offset = static_cast<std::uint16_t>(i);
  out.words = 2;
  out.samples = n;
  const auto fill_in = [&](std::size_t o, InferredKind kind) {
    const PairOrder& s = p.order[o];
    out.kind = kind;
    out.order = o == kHigh ? WordOrder::HighFirst : WordOrder::LowFirst;
    const std::uint16_t a = latest_[i], b = latest_[i + 1];
    const std::uint32_t last = o == kHigh ? join(a, b) : join(b, a);
    const bool is_signed = kind == InferredKind::S32;
    out.min = is_signed ? static_cast<double>(s.imin) : static_cast<double>(s.umin);
    out.max = is_signed ? static_cast<double>(s.imax) : static_cast<double>(s.umax);
    out.last = is_signed ? static_cast<double>(static_cast<std::int32_t>(last))
                         : static_cast<double>(last);
    out.constant = p.changes == 0;
  };
  for (std::size_t o = 0; o < 2; ++o) {
    const PairOrder& s = p.order[o];
    if (s.carries == 0 || s.u32_downs > 0) continue;
    fill_in(o, InferredKind::U32);
    out.counter = true;
    out.wraps = 0;
    out.confidence = 0.9;
    out.evidence = words_of(
        "u32 counter, %s: the low word wrapped %u times as the high word stepped by one, and "
        "the whole never decreased in %u values",
        order_words(o), s.carries, n);
    return true;
  }
  for (std::size_t o = 0; o < 2; ++o) {
    const PairOrder& s = p.order[o];
    const WordStats& high = words_[o == kHigh ? i : i + 1];
    const WordStats& low = words_[o == kHigh ? i + 1 : i];
    if (s.extension != n || low.changes == 0 || high.max != 0xFFFF) continue;
    const bool both = high.min == 0;
    fill_in(o, InferredKind::S32);
    out.confidence = both ? 0.85 : 0.6;
    out.evidence = words_of(
        "s32, %s: the %s word is the sign of the other (0x0000 or 0xFFFF) in all %u values%s",
        order_words(o), o == kHigh ? "first" : "second", n,
        both ? ", both signs seen" : ", always negative");
    return true;
  }
  for (std::size_t o = 0; o < 2; ++o) {
    const WordStats& high = words_[o == kHigh ? i : i + 1];
    const WordStats& low = words_[o == kHigh ? i + 1 : i];
    if (high.changes != 0 || high.min == 0 || high.min > 0xFF || low.downs != 0 || low.ups < 2) {
      continue;
    }
    fill_in(o, InferredKind::U32);
    out.counter = true;
    out.confidence = 0.55;
    out.evidence = words_of(
        "u32 counter, %s: the %s word holds %u in every value while the other only grows "
        "(%u times): a 32-bit counter between carries",
        order_words(o), o == kHigh ? "first" : "second", unsigned{high.min}, low.ups);
    return true;
  }
  return float_pair(i, out);
}

bool BlockInference::float_pair(std::size_t i, InferredValue& out, int prefer) const {
  const std::uint32_t n = samples_;
  const PairStats& p = pairs_[i];
  if (words_[i].max == 0 && words_[i + 1].max == 0) return false;  // zeros read as anything
  const std::uint32_t allowed = n / 50;  // a rare outlier (a damaged value) is forgiven
  std::array<bool, 2> ok{};
  for (std::size_t o = 0; o < 2; ++o) ok[o] = p.order[o].plausible + allowed >= n;
  if (!ok[kHigh] && !ok[kLow]) return false;
  std::size_t o = ok[kHigh] ? kHigh : kLow;
  const bool both = ok[kHigh] && ok[kLow];
  if (both && p.order[kLow].smooth > p.order[kHigh].smooth) o = kLow;
  if (both && p.order[kLow].smooth == p.order[kHigh].smooth && prefer >= 0) {
    o = static_cast<std::size_t>(prefer);
  }
  const PairOrder& s = p.order[o];
  const PairOrder& other = p.order[1 - o];
  const std::uint16_t a = latest_[i], b = latest_[i + 1];
  out = InferredValue{};
  out.offset = static_cast<std::uint16_t>(i);
  out.words = 2;
  out.samples = n;
  out.kind = InferredKind::Float32;
  out.order = o == kHigh ? WordOrder::HighFirst : WordOrder::LowFirst;
  out.constant = p.changes == 0;
  out.min = s.fmin;
  out.max = s.fmax;
  out.last = std::bit_cast<float>(o == kHigh ? join(a, b) : join(b, a));
  const double smooth = p.changes > 0 ? double(s.smooth) / p.changes : 0.5;
  const double other_bad = n > 0 ? double(n - std::min(n, other.plausible)) / n : 0;
  out.confidence = std::min(0.99, 0.35 + 0.3 * smooth + 0.35 * other_bad);
  std::string changes = p.changes > 0 ? words_of(", %u of %u changes smooth", s.smooth, p.changes)
                                      : std::string(", never changed");
  out.evidence = words_of(
      "float32, %s: %u of %u values finite and 0 or within 1e-3..1e6%s; %s would give %u NaN "
      "or infinite and %u out of range",
      order_words(o), s.plausible, n, changes.c_str(), order_words(1 - o), other.not_finite,
      n - std::min(n, other.plausible + other.not_finite));
  out.hint = hint_for(out.min, out.max, out.constant);
  if (both && p.order[kLow].smooth == p.order[kHigh].smooth) {
    out.evidence += prefer >= 0 ? "; both orders read, the block's other floats are "
                                : "; both orders read alike, taken as ";
    out.evidence += order_words(o);
  }
  return true;
}

InferredValue BlockInference::single(std::size_t i) const {
  const WordStats& w = words_[i];
  const std::uint32_t n = samples_;
  InferredValue out;
  out.offset = static_cast<std::uint16_t>(i);
  out.samples = n;
  out.min = w.min;
  out.max = w.max;
  out.last = latest_[i];
  out.constant = w.changes == 0;
  const auto as_signed = [&](double confidence, std::string evidence) {
    out.kind = InferredKind::S16;
    out.min = w.smin;
    out.max = w.smax;
    out.last = static_cast<std::int16_t>(latest_[i]);
    out.confidence = confidence;
    out.evidence = std::move(evidence);
  };
  if (w.fill == n && w.min == w.max) {
    out.kind = InferredKind::Unused;
    out.confidence = n >= 3 ? 0.8 : 0.5;
    out.evidence = words_of(
        "unused: 0x%04X in all %u values (the fill of a register the device "
        "does not have)",
        unsigned{w.min}, n);
    return out;
  }
  if (w.changes == 0) {
    if (w.min >= 0xF000) {
      as_signed(0.4, words_of("constant: %d (0x%04X) in all %u values, a small negative number "
                              "if signed",
                              int{w.smin}, unsigned{w.min}, n));
      return out;
    }
    out.kind = InferredKind::U16;
    out.confidence = 0.4;
    out.evidence =
        words_of("constant: %u (0x%04X) in all %u values", unsigned{w.min}, unsigned{w.min}, n);
    return out;
  }
  if (w.downs == w.wraps && w.ups >= 2 && (w.wraps > 0 || w.ups >= 3)) {
    out.kind = InferredKind::U16;
    out.counter = true;
    out.wraps = w.wraps;
    out.confidence = w.wraps > 0 ? 0.85 : 0.5;
    out.evidence = w.wraps > 0 ? words_of(
                                     "u16 counter: grew %u times and wrapped past 65535 %u "
                                     "times, never otherwise decreased",
                                     w.ups, w.wraps)
                               : words_of(
                                     "u16 counter: grew %u times and never decreased "
                                     "(%u..%u)",
                                     w.ups, unsigned{w.min}, unsigned{w.max});
    return out;
  }
  const unsigned changed = w.changed_bits;
  const bool low_run = (changed & (changed + 1)) == 0;  // only bits 0..k change: a number
  if (!low_run && std::popcount(changed) <= 6 && w.changes >= 2) {
    out.kind = InferredKind::Bits;
    out.changed_bits = w.changed_bits;
    out.confidence = 0.6;
    std::string list;
    for (unsigned b = 0; b < 16; ++b) {
      if ((changed >> b & 1u) == 0) continue;
      if (!list.empty()) list += ' ';
      list += std::to_string(b);
    }
    out.evidence = words_of("bits: only bits %s change (%u changes), in no arithmetic order",
                            list.c_str(), w.changes);
    return out;
  }
  if (w.smin < 0 && w.smax >= 0 && w.step_signed * 4 < w.step_unsigned) {
    as_signed(0.8, words_of("s16: %u values %d..%d; read unsigned they jump by about 65536 "
                            "where the sign changes (mean step %.0f unsigned, %.0f signed)",
                            n, int{w.smin}, int{w.smax}, double(w.step_unsigned) / w.changes,
                            double(w.step_signed) / w.changes));
    return out;
  }
  if (w.min >= 0xF000) {
    as_signed(0.5, words_of("s16: %u values %d..%d, small negative numbers if signed", n,
                            int{w.smin}, int{w.smax}));
    return out;
  }
  out.kind = InferredKind::U16;
  out.confidence = 0.6;
  out.evidence = words_of("u16: %u values %u..%u, mean step %.1f", n, unsigned{w.min},
                          unsigned{w.max}, double(w.step_unsigned) / w.changes);
  return out;
}

std::vector<InferredValue> BlockInference::infer_once(std::size_t from, std::size_t end,
                                                      int prefer) const {
  std::vector<InferredValue> out;
  for (std::size_t i = from; i < end;) {
    InferredValue v;
    if (const std::size_t n = text_run(i, end, v); n > 0) {
      out.push_back(std::move(v));
      i += n;
      continue;
    }
    InferredValue text;
    // Text that starts one word later keeps its first word; a wrapping counter beside a word
    // that never changes is no float.
    const bool text_next = i + 1 < end && text_run(i + 1, end, text) > 0;
    const bool lone_counter = i + 1 < end && words_[i].wraps > 0 &&
                              words_[i].downs == words_[i].wraps && words_[i + 1].changes == 0;
    if (i + 1 < end && !text_next && pair(i, v) &&
        !(lone_counter && v.kind == InferredKind::Float32)) {
      if (v.kind == InferredKind::Float32 && prefer >= 0) float_pair(i, v, prefer);
      // A steady word before a float that reads better one word later (padding, or a value
      // whose zero low word came first) stays a word of its own.
      InferredValue next;
      const bool shifted = v.kind == InferredKind::Float32 && words_[i].changes == 0 &&
                           i + 2 < end && float_pair(i + 1, next, prefer) &&
                           next.confidence > v.confidence;
      if (!shifted) {
        out.push_back(std::move(v));
        i += 2;
        continue;
      }
    }
    out.push_back(single(i));
    ++i;
  }
  return out;
}

std::vector<InferredValue> BlockInference::infer(std::size_t from, std::size_t count) const {
  const std::size_t end = std::min(from + count, words_.size());
  if (samples_ == 0 || from >= end) return {};
  std::vector<InferredValue> out = infer_once(from, end, -1);
  // A device sends all its floats in one word order: a float that reads alike in both takes
  // the order of the block's floats that tell.
  std::array<unsigned, 2> orders{};
  bool ambiguous = false;
  for (const InferredValue& v : out) {
    if (v.kind != InferredKind::Float32) continue;
    const PairStats& p = pairs_[v.offset];
    const bool both = p.order[kHigh].plausible == p.order[kLow].plausible &&
                      p.order[kHigh].smooth == p.order[kLow].smooth;
    if (both) {
      ambiguous = true;
    } else {
      ++orders[v.order == WordOrder::HighFirst ? kHigh : kLow];
    }
  }
  if (!ambiguous || orders[kHigh] == orders[kLow]) return out;
  return infer_once(from, end, orders[kHigh] > orders[kLow] ? int{kHigh} : int{kLow});
}

}  // namespace pvtap
