// The plain Modbus requests and replies of the simulated devices (meter, IO module, battery,
// SunSpec inverter, test server), as typed core Frames (their bytes always come from the
// core's encode_frame): the simulator's part of the plain Modbus dialect.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "pvtap/codec/frame.h"

namespace pvtap::sim {

// Requests. A request of `function` with its station alone (the fields are the caller's).
Frame modbus_request(std::uint8_t station, std::uint8_t function);
Frame modbus_read(std::uint8_t station, std::uint8_t function, std::uint16_t start,
                  std::uint16_t count);
Frame write_single_coil(std::uint8_t station, std::uint16_t coil, bool on);
Frame write_single_register(std::uint8_t station, std::uint16_t address, std::uint16_t value);
Frame write_multiple_registers(std::uint8_t station, std::uint16_t start, const WordList& words);
Frame write_multiple_coils(std::uint8_t station, std::uint16_t start,
                           const std::vector<bool>& states);
// Diagnostics sub-function 0x0000, return query data: the reply echoes `data`.
Frame return_query_data(std::uint8_t station, std::uint16_t data);
// Read device identification, basic stream (read code 1) from object 0x00.
Frame read_device_identification(std::uint8_t station);
Frame report_server_id(std::uint8_t station);

// Replies.
Frame echo_of(const Frame& request);
Frame register_reply(const Frame& request, const WordList& words);
Frame bits_reply(const Frame& request, const std::vector<bool>& bits);
Frame write_multiple_reply(const Frame& request);
Frame exception_reply(const Frame& request, std::uint8_t code);
// Objects 0x00 vendor, 0x01 product code, 0x02 revision, all in one reply (conformity 0x01:
// basic identification, stream access only).
Frame device_identification_reply(const Frame& request, std::string_view vendor,
                                  std::string_view product, std::string_view revision);
// Server ID byte, run indicator 0xFF (running), then `text`.
Frame server_id_reply(const Frame& request, std::uint8_t server_id, std::string_view text);

// The words of an IEEE-754 single, high word first (the usual meter order) unless `low_first`.
void push_float(WordList& words, float value, bool low_first = false);
std::uint32_t float_bits(float value);
// Word `index` of `text` as registers hold it: two characters, high byte first, NUL-padded.
std::uint16_t text_word(std::string_view text, unsigned index);
// The words a device's register read asks for, each from `word_at`.
WordList register_words(const Frame& request,
                        const std::function<std::uint16_t(std::uint16_t)>& word_at);

}  // namespace pvtap::sim
