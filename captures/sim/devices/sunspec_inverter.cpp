#include "devices/sunspec_inverter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bus/frame_shapes.h"
#include "dialects/modbus_frames.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

constexpr std::uint8_t kHolding = fc::kGslReadHolding;
constexpr std::uint16_t kNotImplementedS16 = 0x8000;
constexpr std::uint16_t kNotImplementedU16 = 0xFFFF;

// Model 103's points after its header, as the published model lays them out.
enum Offset103 : std::uint16_t {
  kA = 0,
  kAphA = 1,
  kASf = 4,
  kPPVphAB = 5,
  kPhVphA = 8,
  kVSf = 11,
  kW = 12,
  kWSf = 13,
  kHz = 14,
  kHzSf = 15,
  kVA = 16,
  kVASf = 17,
  kVAr = 18,
  kVArSf = 19,
  kPF = 20,
  kPFSf = 21,
  kWH = 22,
  kWHSf = 24,
  kDCA = 25,
  kDCASf = 26,
  kDCV = 27,
  kDCVSf = 28,
  kDCW = 29,
  kDCWSf = 30,
  kTmpCab = 31,
  kTmpSnk = 32,
  kTmpTrns = 33,
  kTmpOt = 34,
  kTmpSf = 35,
  kSt = 36,
  kStVnd = 37,
};
// Model 160: the scale factors, event word, module count and period; then 20 per module.
enum Offset160 : std::uint16_t {
  kDcaSf160 = 0,
  kDcvSf160 = 1,
  kDcwSf160 = 2,
  kDcwhSf160 = 3,
  kN160 = 6,
  kFixed160 = 8,
  kModule = 20,
  kModDca = 9,
  kModDcv = 10,
  kModDcw = 11,
  kModDcwh = 12,
  kModTms = 14,
  kModTmp = 16,
  kModSt = 17,
};
// The scale factors this device uses: each value is sent as round(value / 10^sf).
constexpr int kSfA = -2, kSfV = -1, kSfW = 0, kSfHz = -2, kSfPF = -1, kSfWH = 0, kSfDCA = -2,
              kSfDCV = -1, kSfTmp = -1, kSfModA = -3, kSfModV = -1, kSfModW = 1;

std::uint16_t sf_word(int sf) {
  return static_cast<std::uint16_t>(static_cast<std::int16_t>(sf));
}
std::uint16_t scaled(double value, int sf) {
  return static_cast<std::uint16_t>(
      static_cast<std::int16_t>(std::lround(value / std::pow(10.0, sf))));
}
double as_sent(double value, int sf) {
  return static_cast<double>(static_cast<std::int16_t>(scaled(value, sf))) * std::pow(10.0, sf);
}

}  // namespace

SunSpecInverter::SunSpecInverter(std::uint8_t station, std::uint64_t seed, Micros start)
    : ModbusDevice(station), random_(seed ^ 0x5A5Aull * (station + 3)), now_(start) {
  energy_wh_ = 1.5e6 + static_cast<double>(random_.between(0, 100000));
  serial_ = "SS" + std::to_string(200000 + random_.between(0, 799999));
}

DeviceLabel SunSpecInverter::label() const {
  return {"sunspec_inverter", {}, {}, {}, {}};
}

std::vector<Frame> SunSpecInverter::requests(unsigned /*round*/) const {
  const std::uint8_t s = station();
  std::vector<Frame> out;
  if (!scanned_) {  // the client's scan: marker, then header by header
    out = {modbus_read(s, kHolding, kBase, 2),    modbus_read(s, kHolding, kCommon, 2),
           modbus_read(s, kHolding, kCommon, 68), modbus_read(s, kHolding, kInverter, 2),
           modbus_read(s, kHolding, kMppt, 2),    modbus_read(s, kHolding, kEnd, 2)};
  }
  out.push_back(modbus_read(s, kHolding, kInverter + 2, 50));
  out.push_back(modbus_read(s, kHolding, kMppt + 2, 48));
  return out;
}

void SunSpecInverter::answered(const Frame& request, bool whole) {
  // The scan reads the marker and each header (two words) and the common model; the polls
  // read 103 and 160 past their headers.
  const bool scan = request.count == 2 || request.start == kCommon;
  if (scanned_ || !scan) return;
  scan_damaged_ = scan_damaged_ || !whole;
  if (request.start == kEnd) {  // the scan's last read
    scanned_ = !scan_damaged_;
    scan_damaged_ = false;
  }
}

void SunSpecInverter::advance(Micros now) {
  const double seconds = static_cast<double>(std::max<Micros>(0, now - now_)) / 1e6;
  now_ = std::max(now, now_);
  const double t = static_cast<double>(now_) / 1e6;
  power_w_ = std::clamp(6000.0 + 2500.0 * std::sin(t / 60.0) + (random_.unit() - 0.5) * 200.0, 0.0,
                        10000.0);
  energy_wh_ += power_w_ * seconds / 3600.0;
  for (double& v : volts_) v = 230.0 + (random_.unit() - 0.5) * 4.0;
  hz_ = 50.0 + (random_.unit() - 0.5) * 0.06;
  cabinet_c_ = std::clamp(cabinet_c_ + (random_.unit() - 0.5) * 0.4, 20.0, 60.0);
}

// Every point this device implements, with its value as the wire carries it (rounded to its
// scale factor), keyed as pvtap names SunSpec points.
std::vector<SunSpecInverter::Point> SunSpecInverter::points() const {
  const auto at103 = [](unsigned o) { return static_cast<std::uint16_t>(kInverter + 2 + o); };
  const double amps = power_w_ / (3.0 * 230.0);
  std::vector<Point> p = {
      {at103(kA), "m103_a", as_sent(amps * 3.0, kSfA), kSfA},
      {at103(kAphA), "m103_apha", as_sent(amps, kSfA), kSfA},
      {at103(kAphA + 1), "m103_aphb", as_sent(amps, kSfA), kSfA},
      {at103(kAphA + 2), "m103_aphc", as_sent(amps, kSfA), kSfA},
      {at103(kPPVphAB), "m103_ppvphab", as_sent(volts_[0] * std::sqrt(3.0), kSfV), kSfV},
      {at103(kPhVphA), "m103_phvpha", as_sent(volts_[0], kSfV), kSfV},
      {at103(kPhVphA + 1), "m103_phvphb", as_sent(volts_[1], kSfV), kSfV},
      {at103(kPhVphA + 2), "m103_phvphc", as_sent(volts_[2], kSfV), kSfV},
      {at103(kW), "m103_w", as_sent(power_w_, kSfW), kSfW},
      {at103(kHz), "m103_hz", as_sent(hz_, kSfHz), kSfHz},
      {at103(kPF), "m103_pf", as_sent(99.0, kSfPF), kSfPF},
      {at103(kWH), "m103_wh", std::floor(energy_wh_), kSfWH},
      {at103(kDCA), "m103_dca", as_sent(power_w_ / 0.97 / 600.0, kSfDCA), kSfDCA},
      {at103(kDCV), "m103_dcv", as_sent(600.0, kSfDCV), kSfDCV},
      {at103(kDCW), "m103_dcw", as_sent(power_w_ / 0.97, kSfW), kSfW},
      {at103(kTmpCab), "m103_tmpcab", as_sent(cabinet_c_, kSfTmp), kSfTmp},
  };
  for (unsigned m = 0; m < 2; ++m) {
    const auto at = [m](unsigned o) {
      return static_cast<std::uint16_t>(kMppt + 2 + kFixed160 + m * kModule + o);
    };
    const std::string k = "m160_" + std::to_string(m + 1) + "_";
    const double watts = power_w_ / 0.97 / 2.0;
    p.push_back({at(kModDca), k + "dca", as_sent(watts / 600.0, kSfModA), kSfModA});
    p.push_back({at(kModDcv), k + "dcv", as_sent(600.0, kSfModV), kSfModV});
    p.push_back({at(kModDcw), k + "dcw", as_sent(watts, kSfModW), kSfModW});
  }
  return p;
}

std::uint16_t SunSpecInverter::word_at(std::uint16_t address,
                                       const std::vector<Point>& points) const {
  if (address == kBase) return 0x5375;
  if (address == kBase + 1) return 0x6E53;
  if (address == kCommon) return 1;
  if (address == kCommon + 1) return 66;
  if (address == kInverter) return 103;
  if (address == kInverter + 1) return 50;
  if (address == kMppt) return 160;
  if (address == kMppt + 1) return 48;
  if (address == kEnd) return 0xFFFF;
  if (address == kEnd + 1) return 0;
  if (address > kCommon + 1 && address < kInverter) {
    const unsigned o = address - (kCommon + 2);
    if (o < 16) return text_word("PVTAP Solar", o);
    if (o < 32) return text_word("SIM-SS-10K", o - 16);
    if (o < 40) return 0;
    if (o < 48) return text_word("2.4.1", o - 40);
    if (o < 64) return text_word(serial_, o - 48);
    return o == 64 ? station() : kNotImplementedS16;
  }
  if (address > kInverter + 1 && address < kMppt) {
    const unsigned o = address - (kInverter + 2);
    switch (o) {
      case kASf:
        return sf_word(kSfA);
      case kVSf:
        return sf_word(kSfV);
      case kWSf:
      case kDCWSf:
        return sf_word(kSfW);
      case kHzSf:
        return sf_word(kSfHz);
      case kVA:
      case kVAr:
        return kNotImplementedS16;
      case kVASf:
      case kVArSf:
        return kNotImplementedS16;
      case kPFSf:
        return sf_word(kSfPF);
      case kWH:
        return static_cast<std::uint16_t>(static_cast<std::uint32_t>(energy_wh_) >> 16);
      case kWH + 1:
        return static_cast<std::uint16_t>(static_cast<std::uint32_t>(energy_wh_));
      case kWHSf:
        return sf_word(kSfWH);
      case kDCASf:
        return sf_word(kSfDCA);
      case kDCVSf:
        return sf_word(kSfDCV);
      case kTmpSnk:
      case kTmpTrns:
      case kTmpOt:
        return kNotImplementedS16;
      case kTmpSf:
        return sf_word(kSfTmp);
      case kSt:
        return 4;  // MPPT
      case kStVnd:
        return kNotImplementedU16;
      default:
        break;
    }
    if (o >= 38) return 0;  // no events
  }
  if (address > kMppt + 1 && address < kEnd) {
    const unsigned o = address - (kMppt + 2);
    switch (o) {
      case kDcaSf160:
        return sf_word(kSfModA);
      case kDcvSf160:
        return sf_word(kSfModV);
      case kDcwSf160:
        return sf_word(kSfModW);
      case kDcwhSf160:
        return 0;
      case kN160:
        return 2;
      case kN160 + 1:
        return 0;
      default:
        break;
    }
    if (o >= kFixed160) {
      const unsigned m = (o - kFixed160) / kModule, k = (o - kFixed160) % kModule;
      if (k == 0) return static_cast<std::uint16_t>(m + 1);
      if (k >= 1 && k < 9) return text_word("MPPT " + std::to_string(m + 1), k - 1);
      if (k == kModTmp) return kNotImplementedS16;
      if (k == kModSt) return 4;
      if (k == kModTms + 1) return static_cast<std::uint16_t>(now_ / 1000000);
      if (k == kModDcwh + 1) return static_cast<std::uint16_t>(energy_wh_ / 2.0);
    }
  }
  for (const Point& p : points) {
    if (p.address == address) return scaled(p.value, p.sf);
  }
  return 0;
}

BusEvent SunSpecInverter::reply(const Frame& request, Micros request_end) {
  advance(request_end);
  // The points are worked out once a reply: every word of the read looks into them.
  const std::vector<Point> now = points();
  const WordList words = register_words(request, [&](std::uint16_t a) { return word_at(a, now); });
  BusEvent e = frame_event(register_reply(request, words));
  const std::uint16_t start = request.start.value_or(0), count = request.count.value_or(0);
  for (const Point& p : now) {
    if (p.address < start || p.address >= start + count) continue;
    RegisterTruth t;
    char address[8];
    std::snprintf(address, sizeof address, "0x%04X", unsigned{p.address});
    t.address = address;
    t.key = p.key;
    t.value = p.value;
    t.numeric = true;
    e.values.push_back(std::move(t));
  }
  return e;
}

}  // namespace pvtap::sim
