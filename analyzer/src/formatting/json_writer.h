// JsonWriter: JSON objects and arrays appended to a string, the one way pvtap writes JSON.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

#include "formatting/json_text.h"
#include "formatting/number_text.h"

namespace pvtap::analyzer {

// A member name spelled in the program. Checked at compile time to need no escape and to fit
// the writer's buffer, so that writing it is one copy, not a scan.
class JsonKey {
 public:
  static constexpr std::size_t kMaxSize = 48;

  template <std::size_t N>
  consteval JsonKey(const char (&name)[N]) : name_(name, N - 1) {
    static_assert(N - 1 <= kMaxSize, "a JSON key longer than JsonKey::kMaxSize");
    for (const char c : name_) {
      // Not a constant expression, so a key that needs escaping does not compile.
      if (static_cast<unsigned char>(c) < 0x20 || c == '"' || c == '\\') throw "escape";
    }
  }

  constexpr std::string_view text() const { return name_; }

 private:
  std::string_view name_;
};

// Appends to `out`; places commas, quotes and colons itself. Nesting is kept as one bit per
// open level ("has it a member yet"), so a writer is three words and never allocates; 63
// levels deep at most. A writer from more_members() with nothing open makes a list of members
// (`,"a":1,"b":2`) for raw_members() of another writer: how fixed parts of a line are rendered
// once and kept.
class JsonWriter {
 public:
  explicit JsonWriter(std::string& out) : out_(out) {}

  // A writer for more members of an object that another writer holds open and has written
  // members in already. A function that adds members is handed one of these rather than the
  // caller's writer by reference, so that the caller's state stays in registers.
  static JsonWriter more_members(std::string& out) {
    JsonWriter w(out);
    w.members_ = 1;
    return w;
  }

  std::string& buffer() { return out_; }

  void begin_object() { open('{'); }
  void end_object() { close('}'); }
  void begin_array() { open('['); }
  void end_array() { close(']'); }
  // The member `name` opened as an object or an array: `,"name":{` copied at once.
  [[gnu::always_inline]] void begin_object(JsonKey name) {
    put_key(name, '{');
    members_ <<= 1;
  }
  [[gnu::always_inline]] void begin_array(JsonKey name) {
    put_key(name, '[');
    members_ <<= 1;
  }

  // Inlined always: only where the key is a constant does its copy fold to a few stores.
  [[gnu::always_inline]] void key(JsonKey name) {
    put_key(name, '\0');
    after_key_ = true;
  }
  // A member name made at run time (a station's name, a function's): escaped.
  void key_text(std::string_view name) {
    member_start();
    append_json_string(out_, name);
    out_ += ':';
    after_key_ = true;
  }

  void string(std::string_view text) {
    value_start();
    append_json_string(out_, text);
  }
  // A string the program spells itself (a dialect, a role, a verdict): quoted, not scanned.
  [[gnu::always_inline]] void plain_string(std::string_view text) {
    value_start();
    out_ += '"';
    out_ += text;
    out_ += '"';
  }
  // Bytes as one lowercase hex string ("0103").
  void hex(std::span<const std::uint8_t> bytes) {
    value_start();
    out_ += '"';
    append_hex(out_, bytes);
    out_ += '"';
  }
  void uint(std::uint64_t value) {
    value_start();
    append_uint(out_, value);
  }
  void integer(std::int64_t value) {
    value_start();
    append_int(out_, value);
  }
  void fixed(double value, int decimals) {
    value_start();
    append_fixed(out_, value, decimals);
  }
  void boolean(bool value) {
    value_start();
    out_ += value ? std::string_view("true") : std::string_view("false");
  }
  void null() {
    value_start();
    out_ += "null";
  }
  // Where a value goes that another formatter appends (register readings): what goes before
  // a value is placed, and the buffer returned.
  std::string& value_out() {
    value_start();
    return out_;
  }
  // A value that is JSON text already (a number written elsewhere, a kept fragment).
  void raw(std::string_view json) {
    value_start();
    out_ += json;
  }
  // Members that are JSON text already, made by a writer from more_members() so that they
  // begin with their comma (not empty); the comma is dropped where they come first. The last
  // may be a key whose value comes next (`,"a":1,"b":`).
  void raw_members(std::string_view members) {
    if (!separated()) members.remove_prefix(1);
    out_ += members;
    after_key_ = ends_at_key(members);
  }
  // An object opened by kept text that a writer made and left open (`{"a":1,"b":`): the
  // parts of a line that repeat, rendered once.
  void raw_object_start(std::string_view kept) {
    value_start();
    out_ += kept;
    members_ = (members_ << 1) | 1;
    after_key_ = ends_at_key(kept);
  }

  void field(JsonKey name, std::string_view text) {
    key(name);
    string(text);
  }
  template <std::size_t N>
  void field(JsonKey name, const char (&text)[N]) {
    key(name);
    string(std::string_view(text, N - 1));
  }
  template <std::unsigned_integral T>
  requires(!std::same_as<T, bool>) void field(JsonKey name, T value) {
    key(name);
    uint(value);
  }
  template <std::signed_integral T>
  void field(JsonKey name, T value) {
    key(name);
    integer(value);
  }
  // Not a string: a pointer would otherwise become a bool.
  void field(JsonKey name, bool value) = delete;

  [[gnu::always_inline]] void field_plain(JsonKey name, std::string_view text) {
    key(name);
    plain_string(text);
  }
  // A member whose value is a literal of the program: `,"name":"text"` copied at once.
  template <std::size_t N>
  [[gnu::always_inline]] void field_plain(JsonKey name, const char (&text)[N]) {
    const std::string_view n = name.text();
    char member[JsonKey::kMaxSize + N + 5];
    member[0] = ',';
    member[1] = '"';
    std::memcpy(member + 2, n.data(), n.size());
    member[n.size() + 2] = '"';
    member[n.size() + 3] = ':';
    member[n.size() + 4] = '"';
    std::memcpy(member + n.size() + 5, text, N - 1);
    member[n.size() + N + 4] = '"';
    const std::size_t skip = separated() ? 0 : 1;
    out_.append(member + skip, n.size() + N + 5 - skip);
  }
  void field_fixed(JsonKey name, double value, int decimals) {
    key(name);
    fixed(value, decimals);
  }
  void field_bool(JsonKey name, bool value) {
    key(name);
    boolean(value);
  }
  void field_null(JsonKey name) {
    key(name);
    null();
  }
  [[gnu::always_inline]] void field_hex(JsonKey name, std::span<const std::uint8_t> bytes) {
    put_key(name, '"');
    append_hex(out_, bytes);
    out_ += '"';
  }
  void field_raw(JsonKey name, std::string_view json) {
    key(name);
    raw(json);
  }

 private:
  // `,"name":` and what opens its value (`then`: a bracket or a quote, or '\0' for nothing)
  // copied at once, the comma only after a member: the key is a constant, so this folds to a
  // few stores.
  [[gnu::always_inline]] void put_key(JsonKey name, char then) {
    const std::string_view n = name.text();
    char text[JsonKey::kMaxSize + 5];
    text[0] = ',';
    text[1] = '"';
    std::memcpy(text + 2, n.data(), n.size());
    text[n.size() + 2] = '"';
    text[n.size() + 3] = ':';
    text[n.size() + 4] = then;
    const std::size_t skip = separated() ? 0 : 1;
    const std::size_t opener = then != '\0' ? 1 : 0;
    out_.append(text + skip, n.size() + 4 + opener - skip);
  }
  // True when the open level has a member already (a comma goes first); marks it as having one.
  bool separated() {
    const bool had = (members_ & 1) != 0;
    members_ |= 1;
    return had;
  }
  // JSON text ends with ':' only after a key (a string ends with '"').
  static bool ends_at_key(std::string_view json) { return !json.empty() && json.back() == ':'; }
  void member_start() {
    if (separated()) out_ += ',';
  }
  void value_start() {
    if (after_key_) {
      after_key_ = false;
    } else {
      member_start();
    }
  }
  void open(char bracket) {
    value_start();
    out_ += bracket;
    members_ <<= 1;
  }
  void close(char bracket) {
    members_ >>= 1;
    out_ += bracket;
  }

  std::string& out_;
  std::uint64_t members_ = 0;  // bit 0: the innermost open level
  bool after_key_ = false;
};

}  // namespace pvtap::analyzer
