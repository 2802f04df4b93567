// pvtap-core-demo: the protocol core at work on the test vectors of PROTOCOLS.md section 5.
//
// Part 1 takes each vector alone: probe_frame finds its dialect, role and length,
// parse_frame decodes it, and the check verdict is compared with the reference's.
// Part 2 joins all vectors into one byte stream with noise between the exchanges, as a
// serial-to-TCP gateway or a bus tap might deliver it, and shows what a scan finds.
// Exits 1 when the core disagrees with the reference anywhere, 0 otherwise.

#include <algorithm>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pvtap/codec/dialect.h"
#include "pvtap/codec/frame.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/framing/framing_probe.h"
#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_format.h"
#include "pvtap/statistics/bus_timing.h"

namespace {

using pvtap::Dialect;
using pvtap::Role;
using Bytes = std::vector<std::uint8_t>;

// One worked example of PROTOCOLS.md section 5 with the reference's verdict.
struct TestVector {
  const char* hex;  // bytes as on the wire
  Dialect dialect;
  Role role;                 // who sends it: the master (request) or an inverter (response)
  const char* bad_expected;  // nullptr when the check is good; else the correct check bytes
  const char* meaning;
  bool starts_exchange;  // in the stream of part 2, noise may come before it
};

constexpr TestVector kVectors[] = {
    {"05 30 31 52 30 30 30 34 30 34 30 31 64 62 04", Dialect::Ascii, Role::Request, nullptr,
     "read faults", true},
    {"05 30 31 52 30 30 32 30 30 32 30 31 64 37 04", Dialect::Ascii, Role::Request, nullptr,
     "read PV", true},
    {"05 30 31 52 30 30 35 30 30 37 30 31 64 66 04", Dialect::Ascii, Role::Request, nullptr,
     "read line", true},
    {"05 30 31 52 30 30 36 30 30 38 30 31 65 31 04", Dialect::Ascii, Role::Request, nullptr,
     "read power", true},
    {"05 30 31 52 30 31 65 30 30 33 30 32 30 63 04", Dialect::Ascii, Role::Request, nullptr,
     "read system", true},
    {"FF 11 10 60 00 02 6D 08", Dialect::Hybrid, Role::Request, nullptr,
     "broadcast device-info request", true},
    {"06 11 08 31 00 00 67 31 00 00 67 93 3A", Dialect::Hybrid, Role::Response, "97 FA",
     "device info, inverter no. 103", false},
    {"09 11 08 22 00 00 6B 22 00 00 6B F2 77", Dialect::Hybrid, Role::Response, nullptr,
     "device info, PWM controller no. 107", false},
    {"06 18 10 2A 09 3C 03 36", Dialect::Hybrid, Role::Request, nullptr, "set 0x102A to 236.4 V",
     true},
    {"06 18 08 31 00 00 67 10 2A 09 3C 2A 86", Dialect::Hybrid, Role::Response, "2B 8A", "its echo",
     false},
    {"06 1F 10 24 00 7B 91 57", Dialect::Hybrid, Role::Request, nullptr, "restore factory settings",
     true},
    {"06 1F 08 31 00 00 67 10 24 00 7B BD F1", Dialect::Hybrid, Role::Response, nullptr,
     "its confirmation", false},
    {"06 FF 08 31 00 00 67 10 00 00 FF F8 C3", Dialect::Hybrid, Role::Response, "F9 CF",
     "error reply", false},
    {"01 03 00 00 00 0A C5 CD", Dialect::Gsl, Role::Request, nullptr, "read 10 registers from 0",
     true},
};

// Noise put before each exchange in the stream of part 2: break conditions, idle-line
// glitches and stray bytes of the kinds a gateway passes on.
const Bytes kNoise[] = {{0x00},       {0xF0, 0x00}, {0x80}, {0x00, 0xE0, 0x00},
                        {0xFE, 0x00}, {0x00},       {0xF8}, {0x00, 0x00}};

__attribute__((format(printf, 1, 2))) std::string format(const char* fmt, ...) {
  char buf[256];
  va_list args;
  va_start(args, fmt);
  const int n = std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  if (n < 0) return {};
  return std::string(buf, std::min(static_cast<std::size_t>(n), sizeof buf - 1));
}

Bytes parse_hex(std::string_view text) {
  Bytes out;
  unsigned value = 0;
  int digits = 0;
  for (char c : text) {
    int d = -1;
    if (c >= '0' && c <= '9') d = c - '0';
    if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
    if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    if (d < 0) continue;
    value = value * 16 + static_cast<unsigned>(d);
    if (++digits == 2) {
      out.push_back(static_cast<std::uint8_t>(value));
      value = 0;
      digits = 0;
    }
  }
  return out;
}

std::string hex(std::span<const std::uint8_t> bytes) {
  std::string out;
  for (std::uint8_t b : bytes) {
    if (!out.empty()) out += ' ';
    out += format("%02X", b);
  }
  return out;
}

// The check bytes as a person reads them: RTU as hex bytes, ASCII as its four characters.
std::string check_text(Dialect d, std::span<const std::uint8_t> wire) {
  if (d != Dialect::Ascii) return hex(wire);
  return std::string(wire.begin(), wire.end());
}

std::string station_text(const pvtap::Frame& f) {
  if (f.dialect == Dialect::Hybrid && f.role == Role::Request &&
      f.station == pvtap::fc::kHybridBroadcast)
    return "all";
  return format("%u", static_cast<unsigned>(f.station));
}

// start/count, register = value, device number, word count, exception: whatever the frame has.
std::string fields_text(const pvtap::Frame& f) {
  std::string out;
  auto add = [&out](const std::string& part) {
    if (!out.empty()) out += ", ";
    out += part;
  };
  if (f.device) {
    // The type names (table H5) live in the Hybrid register map, like every protocol fact.
    const pvtap::DecodedValue device = pvtap::RegisterDecoder().decode_device_number(*f.device);
    add("device " + pvtap::format_value(device));
  }
  const bool reg_value = f.start && !f.count && f.words.size() == 1;
  if (reg_value) {
    add(format("reg 0x%04X = 0x%04X", static_cast<unsigned>(*f.start),
               static_cast<unsigned>(f.words[0])));
  } else {
    if (f.start) add(format("start 0x%04X", static_cast<unsigned>(*f.start)));
    if (f.count) add(format("count %u", static_cast<unsigned>(*f.count)));
    if (!f.words.empty()) add(format("%zu words", f.words.size()));
  }
  if (f.exception_code) {
    add(format("exception %02X (%s)", static_cast<unsigned>(*f.exception_code),
               std::string(pvtap::fc::exception_name(*f.exception_code)).c_str()));
  }
  return out;
}

std::string verdict_text(Dialect d, std::span<const std::uint8_t> frame,
                         const pvtap::FrameCheck& check) {
  const std::size_t check_len = d == Dialect::Ascii ? 4 : 2;
  const std::size_t tail = d == Dialect::Ascii ? 1 : 0;  // EOT
  std::span<const std::uint8_t> found;
  if (frame.size() >= check_len + tail)
    found = frame.subspan(frame.size() - tail - check_len, check_len);
  if (check.ok) return format("good (%s)", check_text(d, found).c_str());
  const Bytes expected = pvtap::check_wire_bytes(d, check.expected);
  return format("BAD: expected %s, found %s", check_text(d, expected).c_str(),
                check_text(d, found).c_str());
}

// A table whose columns are as wide as their widest cell.
class Table {
 public:
  explicit Table(std::vector<std::string> header) { rows_.push_back(std::move(header)); }
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  void print() const {
    std::vector<std::size_t> width;
    for (const auto& row : rows_) {
      if (width.size() < row.size()) width.resize(row.size(), 0);
      for (std::size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
    }
    for (const auto& row : rows_) {
      std::string line = " ";
      for (std::size_t i = 0; i < row.size(); ++i) {
        line += row[i];
        if (i + 1 < row.size()) line.append(width[i] - row[i].size() + 2, ' ');
      }
      std::printf("%s\n", line.c_str());
    }
  }

 private:
  std::vector<std::vector<std::string>> rows_;
};

// The cells shared by both parts: dialect, role, station, function, fields, check.
std::vector<std::string> frame_cells(std::span<const std::uint8_t> bytes, Dialect d, Role r,
                                     const pvtap::FrameCheck& check) {
  const pvtap::ParseOutcome parsed = pvtap::parse_frame(bytes, d, r);
  std::vector<std::string> cells{std::string(pvtap::to_string(d)),
                                 std::string(pvtap::to_string(r))};
  if (parsed) {
    const pvtap::Frame& f = parsed.value();
    cells.push_back(station_text(f));
    cells.push_back(format("%02X %s", static_cast<unsigned>(f.function),
                           std::string(pvtap::fc::function_name(d, f.function)).c_str()));
    cells.push_back(fields_text(f));
  } else {
    cells.push_back("-");
    cells.push_back("-");
    cells.push_back(format("malformed: %s", parsed.error_text().c_str()));
  }
  cells.push_back(verdict_text(d, bytes, check));
  return cells;
}

// Part 1: every vector alone, probed with the direction the reference gives it.
int show_vectors(const std::vector<Bytes>& vectors) {
  std::printf("Part 1: the test vectors of PROTOCOLS.md section 5, one at a time\n");
  std::printf(
      "(probe_frame with the sender known, then parse_frame; 'ref' compares the\n"
      " result with the reference's dialect, role, length and check verdict)\n\n");
  Table table({"#", "dialect", "role", "stn", "function", "fields", "ref", "check"});
  std::vector<std::string> disagreements;
  for (std::size_t i = 0; i < vectors.size(); ++i) {
    const TestVector& v = kVectors[i];
    const Bytes& bytes = vectors[i];
    const pvtap::RoleHint hint =
        v.role == Role::Request ? pvtap::RoleHint::Request : pvtap::RoleHint::Response;
    const pvtap::ProbeResult probe = pvtap::probe_frame(bytes, hint);
    std::string why;
    if (probe.status != pvtap::ProbeResult::Status::Complete) {
      why = "probe found no complete frame";
    } else if (probe.length != bytes.size()) {
      why = format("probe length %zu, not %zu", probe.length, bytes.size());
    } else if (probe.dialect != v.dialect || probe.role != v.role) {
      why = format("probe read it as %s %s", std::string(pvtap::to_string(probe.dialect)).c_str(),
                   std::string(pvtap::to_string(probe.role)).c_str());
    } else if (!pvtap::parse_frame(bytes, probe.dialect, probe.role)) {
      why = "parse_frame rejected it";
    } else if (probe.check.ok != (v.bad_expected == nullptr)) {
      why = v.bad_expected ? "reference says BAD" : "reference says good";
    } else if (v.bad_expected &&
               hex(pvtap::check_wire_bytes(v.dialect, probe.check.expected)) != v.bad_expected) {
      why = format("reference expects %s", v.bad_expected);
    }
    std::vector<std::string> row{format("%zu", i + 1)};
    if (probe.status == pvtap::ProbeResult::Status::Complete && probe.length <= bytes.size()) {
      auto cells =
          frame_cells(std::span(bytes).first(probe.length), probe.dialect, probe.role, probe.check);
      cells.insert(cells.end() - 1, why.empty() ? "ok" : "DIFFERS");
      row.insert(row.end(), cells.begin(), cells.end());
    } else {
      row.insert(row.end(), {"-", "-", "-", "-", "-", "DIFFERS", "-"});
    }
    table.add(std::move(row));
    if (!why.empty())
      disagreements.push_back(format("#%zu (%s): %s", i + 1, v.meaning, why.c_str()));
  }
  table.print();
  for (const std::string& d : disagreements) std::printf(" DIFFERS %s\n", d.c_str());
  return static_cast<int>(disagreements.size());
}

// Part 2: all vectors in one stream with noise between exchanges, as a bus tap at 9600 baud
// would read them: 5-byte reads stamped with the time of their last byte, a silence after
// each frame, no hint about the sender; through the core's stream reassembler.
struct StreamEvent {
  bool is_frame;
  std::uint64_t offset;
  Bytes bytes;
  Dialect dialect;
  Role role;
  pvtap::FrameCheck check;
};

class CollectingSink : public pvtap::ReassemblerSink {
 public:
  void on_frame(const pvtap::FrameEvent& e) override {
    events.push_back(
        {true, e.offset, Bytes(e.bytes.begin(), e.bytes.end()), e.dialect, e.role, e.check});
  }
  void on_noise(const pvtap::NoiseEvent& e) override {
    events.push_back(
        {false, e.offset, Bytes(e.bytes.begin(), e.bytes.end()), Dialect::Gsl, Role::Request, {}});
  }
  std::vector<StreamEvent> events;
};

int show_stream(const std::vector<Bytes>& vectors) {
  Bytes stream;
  std::vector<std::size_t> starts;     // where each vector begins in the stream
  std::vector<std::size_t> item_ends;  // where each burst (noise or frame) ends
  std::size_t noise_bytes = 0;
  std::size_t noise_next = 0;
  for (std::size_t i = 0; i < vectors.size(); ++i) {
    if (kVectors[i].starts_exchange) {
      const Bytes& noise = kNoise[noise_next++ % std::size(kNoise)];
      stream.insert(stream.end(), noise.begin(), noise.end());
      noise_bytes += noise.size();
      item_ends.push_back(stream.size());
    }
    starts.push_back(stream.size());
    stream.insert(stream.end(), vectors[i].begin(), vectors[i].end());
    item_ends.push_back(stream.size());
  }
  std::printf("\nPart 2: the same frames in one stream of %zu bytes, %zu of them noise,\n",
              stream.size(), noise_bytes);
  std::printf(
      "read as a 9600-baud tap would: 5 bytes at a time, timestamped, 5 ms of silence after\n"
      "each burst, no hint about the sender (StreamReassembler)\n\n");

  CollectingSink sink;
  pvtap::StreamReassembler reassembler({}, sink);
  const pvtap::BusTiming timing(9600);
  const std::span<const std::uint8_t> all(stream);
  double now = 0.0;
  std::size_t at = 0;
  for (const std::size_t end : item_ends) {
    while (at < end) {
      const std::size_t n = std::min<std::size_t>(5, end - at);
      now += static_cast<double>(n) * timing.char_time;
      reassembler.feed({all.subspan(at, n), now, pvtap::Direction::Unknown});
      at += n;
    }
    now += 0.005;
    reassembler.idle(now);
  }
  reassembler.finish();

  Table table({"offset", "len", "dialect", "role", "stn", "function", "fields", "check"});
  std::size_t frames = 0;
  std::size_t bad = 0;
  std::size_t noise_found = 0;
  bool same = true;
  for (const StreamEvent& e : sink.events) {
    std::vector<std::string> row{format("%llu", static_cast<unsigned long long>(e.offset)),
                                 format("%zu", e.bytes.size())};
    if (!e.is_frame) {
      noise_found += e.bytes.size();
      row.insert(row.end(), {"noise", "", "", "", hex(e.bytes)});
      table.add(std::move(row));
      continue;
    }
    // The reassembler must find exactly the vectors, in order, with the reference's verdicts.
    same = same && frames < vectors.size() && e.offset == starts[frames] &&
           e.bytes == vectors[frames] && e.check.ok == (kVectors[frames].bad_expected == nullptr);
    ++frames;
    if (!e.check.ok) ++bad;
    const auto cells = frame_cells(e.bytes, e.dialect, e.role, e.check);
    row.insert(row.end(), cells.begin(), cells.end());
    table.add(std::move(row));
  }
  table.print();
  same = same && frames == vectors.size() && noise_found == noise_bytes;
  std::printf("\nfound %zu frames (%zu with a bad check) and %zu noise bytes: %s\n", frames, bad,
              noise_found, same ? "as the reference says" : "DIFFERS from the reference");
  return same ? 0 : 1;
}

}  // namespace

int main() {
  std::vector<Bytes> vectors;
  for (const TestVector& v : kVectors) vectors.push_back(parse_hex(v.hex));

  const int disagreements = show_vectors(vectors);
  const int stream_differs = show_stream(vectors);
  if (disagreements > 0) {
    std::printf("%d vector(s) disagree with the reference\n", disagreements);
  }
  return disagreements == 0 && stream_differs == 0 ? 0 : 1;
}
