// FileFormat: what a file holds, told from its first bytes rather than its name: a capture
// (pcap, pcapng), a sigrok session (a zip), a VCD, other text, or none of these.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace pvtap {

enum class FileFormat { Pcap, Pcapng, Zip, Vcd, Text, Unknown, Unreadable };

// Enough of a file's start to tell every format above.
inline constexpr std::size_t kFormatProbeBytes = 16;

FileFormat file_format_of(std::span<const std::uint8_t> first_bytes);
// The format of the file at `path`; Unreadable when it cannot be opened or is empty.
FileFormat file_format_of(const std::string& path);

// "50 4b 03 04 14 00 08 00 ('PK......')": the first bytes in hex and as text, to say what a
// file that is no capture looks like.
std::string first_bytes_text(const std::string& path);

}  // namespace pvtap
