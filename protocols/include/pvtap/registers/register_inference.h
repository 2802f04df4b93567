// Register inference: what the words no map names probably hold, from every value a capture
// shows of one polled block. Plain rules and statistics over the samples, each verdict with a
// confidence and its evidence in words; no map, no I/O, no allocation per sample.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pvtap/registers/register_map.h"

namespace pvtap {

// InferredKind: how the words of an inferred value hold it.
enum class InferredKind : std::uint8_t {
  U16,      // unsigned word
  S16,      // two's complement word
  U32,      // two words, unsigned
  S32,      // two words, two's complement
  Float32,  // IEEE-754 single over two words
  Text,     // ASCII, two characters a word, high byte first
  Bits,     // flags
  Unused,   // fill: 0xFFFF or 0x8000 in every value
};

// "u16", "s16", "u32", "s32", "float32", "text", "bits", "unused".
std::string_view to_string(InferredKind kind);

// InferredValue: one value of a block: where, what, how sure and why.
struct InferredValue {
  std::uint16_t offset = 0;  // its first word, counted from the block's start
  std::uint16_t words = 1;
  InferredKind kind = InferredKind::U16;
  WordOrder order = WordOrder::HighFirst;  // two-word kinds
  bool constant = false;                   // the same in every value
  bool counter = false;                    // never decreases but by wrapping
  std::uint32_t wraps = 0;                 // of a counter
  std::uint16_t changed_bits = 0;          // Bits: the flags seen to change
  double confidence = 0;                   // 0..1
  std::uint32_t samples = 0;
  double min = 0, max = 0, last = 0;  // the values as the kind reads them (not Text)
  std::string text;                   // Text: the last text
  std::string evidence;               // in words, the numbers behind the verdict
  std::string hint;                   // a plausible physical meaning, when its range fits one
};

// BlockInference: the statistics of one polled block of `words` words, fed with every reply
// to it. Memory is fixed when it is made; add() does not allocate.
class BlockInference {
 public:
  explicit BlockInference(std::size_t words);

  // One reply's words; a reply of another length is not counted.
  void add(std::span<const std::uint16_t> words);
  std::uint32_t samples() const { return samples_; }
  std::size_t size() const { return words_.size(); }

  // The values of words [from, from + count) of the block (a run no map names), left to right.
  std::vector<InferredValue> infer(std::size_t from, std::size_t count) const;

 private:
  // WordStats: what one word of the block did over the samples.
  struct WordStats {
    std::uint16_t first = 0, last = 0, min = 0xFFFF, max = 0;
    std::int16_t smin = 0x7FFF, smax = -0x8000;
    std::uint32_t changes = 0, ups = 0, downs = 0, wraps = 0;
    std::uint32_t fill = 0;       // 0xFFFF or 0x8000
    std::uint32_t printable = 0;  // both bytes printable ASCII or NUL, not both NUL
    std::uint32_t nul = 0;        // both bytes NUL
    std::uint64_t step_unsigned = 0, step_signed = 0;  // sums of |change| as u16 and s16
    std::uint16_t changed_bits = 0;
  };
  // PairOrder: two neighbouring words read as one value in one word order.
  struct PairOrder {
    std::uint32_t plausible = 0;  // finite float, 0 or 1e-3 <= |x| <= 1e6
    std::uint32_t not_finite = 0;
    std::uint32_t smooth = 0;     // float changes within 10 % (of the larger)
    std::uint32_t carries = 0;    // the low word wrapped as the high word stepped by one
    std::uint32_t extension = 0;  // the high word is the low word's sign (0x0000/0xFFFF)
    std::uint32_t u32_downs = 0;  // the 32-bit value decreased
    float fmin = 0, fmax = 0;
    std::uint32_t umin = 0xFFFFFFFF, umax = 0;
    std::int32_t imin = 0x7FFFFFFF, imax = -0x7FFFFFFF - 1;
  };
  struct PairStats {
    PairOrder order[2];  // WordOrder::HighFirst, LowFirst
    std::uint32_t changes = 0;
  };

  InferredValue single(std::size_t i) const;
  bool pair(std::size_t i, InferredValue& out) const;
  // `prefer`: the word order of the block's other floats, for a pair that reads in both.
  bool float_pair(std::size_t i, InferredValue& out, int prefer = -1) const;
  std::vector<InferredValue> infer_once(std::size_t from, std::size_t end, int prefer) const;
  std::size_t text_run(std::size_t i, std::size_t end, InferredValue& out) const;
  void pair_sample(std::size_t i, std::uint16_t a, std::uint16_t b);

  std::vector<WordStats> words_;
  std::vector<PairStats> pairs_;  // pairs_[i]: words i and i + 1
  std::vector<std::uint16_t> latest_;
  std::uint32_t samples_ = 0;
};

}  // namespace pvtap
