// read_logic_file: libsigrok's session loading or its input modules, one datafeed for both.
#include "logic/input/sigrok_file.h"

#include "logic/input/sigrok_library.h"

#include <algorithm>
#include <cstdio>
#include <memory>

namespace pvtap::analyzer {
namespace {

constexpr std::size_t kReadChunk = 1 << 20;

// Feed: what the datafeed callback needs to reach the sink.
struct Feed {
  Feed(const SigrokLibrary& l, LogicSink& s) : sr(l), sink(s) {}
  const SigrokLibrary& sr;
  LogicSink& sink;
  sr_session* session = nullptr;
  bool begun = false;
  double sample_rate = 0;
  double given_rate = 0;  // in place of the file's
  std::vector<LogicChannel> channels;
};

double configured_rate(const SigrokLibrary& sr, const sr_dev_inst* sdi) {
  GVariant* value = nullptr;
  sr_dev_driver* driver = sr.dev_inst_driver_get(sdi);
  if (driver == nullptr || sr.config_get(driver, sdi, nullptr, SR_CONF_SAMPLERATE, &value) != SR_OK)
    return 0;
  const double rate = static_cast<double>(sr.variant_get_uint64(value));
  sr.variant_unref(value);
  return rate;
}

void learn_channels(Feed& f, const sr_dev_inst* sdi) {
  f.channels.clear();
  for (GSList* l = f.sr.dev_inst_channels_get(sdi); l != nullptr; l = l->next) {
    const auto* ch = static_cast<const sr_channel*>(l->data);
    if (ch->type != SR_CHANNEL_LOGIC || !ch->enabled) continue;
    f.channels.push_back(LogicChannel{ch->name, static_cast<unsigned>(ch->index)});
  }
  // A CSV export's header can name every column alike ("logic"): such channels go by their
  // index, so that each name picks one channel.
  std::vector<LogicChannel> named = f.channels;
  for (LogicChannel& c : f.channels) {
    const auto same = std::count_if(named.begin(), named.end(),
                                    [&](const LogicChannel& o) { return o.name == c.name; });
    if (same > 1) c.name = std::to_string(c.index);
  }
  if (f.sample_rate == 0) f.sample_rate = configured_rate(f.sr, sdi);
}

void meta(Feed& f, const sr_datafeed_meta* m) {
  for (GSList* l = m->config; l != nullptr; l = l->next) {
    const auto* c = static_cast<const sr_config*>(l->data);
    if (c->key == SR_CONF_SAMPLERATE)
      f.sample_rate = static_cast<double>(f.sr.variant_get_uint64(c->data));
  }
}

void on_packet(const sr_dev_inst* sdi, const sr_datafeed_packet* packet, void* data) {
  Feed& f = *static_cast<Feed*>(data);
  if (packet->type == SR_DF_META) meta(f, static_cast<const sr_datafeed_meta*>(packet->payload));
  if (packet->type != SR_DF_LOGIC || !f.sink.wants_more()) return;
  if (!f.begun) {
    learn_channels(f, sdi);
    f.sink.begin(f.channels, f.given_rate > 0 ? f.given_rate : f.sample_rate);
    f.begun = true;
  }
  const auto* logic = static_cast<const sr_datafeed_logic*>(packet->payload);
  f.sink.samples({static_cast<const std::uint8_t*>(logic->data), logic->length}, logic->unitsize);
  if (!f.sink.wants_more() && f.session != nullptr) f.sr.session_stop(f.session);
}

struct Context {
  const SigrokLibrary& sr;
  sr_context* ctx = nullptr;
  explicit Context(const SigrokLibrary& l) : sr(l) {
    sr.log_loglevel_set(SR_LOG_NONE);
    if (sr.init(&ctx) != SR_OK) ctx = nullptr;
  }
  ~Context() {
    if (ctx != nullptr) sr.exit(ctx);
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
};

std::string read_session_file(sr_session* session, Feed& feed) {
  const SigrokLibrary& sr = feed.sr;
  feed.session = session;
  sr.session_datafeed_callback_add(session, on_packet, &feed);
  std::string error;
  if (sr.session_start(session) != SR_OK || sr.session_run(session) != SR_OK) {
    error = "libsigrok could not read the session";
  }
  sr.session_destroy(session);
  return error;
}

// An input module reads the file as it is handed chunks; its device exists once it has read
// the file's header, and only then can the session carry its packets.
std::string read_with_input(const std::string& path, const sr_input* in, sr_context* ctx,
                            Feed& feed) {
  const SigrokLibrary& sr = feed.sr;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  sr_session* session = nullptr;
  if (!file || sr.session_new(ctx, &session) != SR_OK) return "cannot open the file";
  sr.session_datafeed_callback_add(session, on_packet, &feed);
  GString* buffer = sr.string_sized_new(kReadChunk);
  std::vector<char> chunk(kReadChunk);
  bool added = false;
  std::string error;
  while (error.empty() && feed.sink.wants_more()) {
    const std::size_t n = std::fread(chunk.data(), 1, chunk.size(), file.get());
    if (n == 0) break;
    sr.string_truncate(buffer, 0);
    sr.string_append_len(buffer, chunk.data(), static_cast<gssize>(n));
    if (sr.input_send(in, buffer) != SR_OK) error = "libsigrok could not read the file";
    sr_dev_inst* sdi = sr.input_dev_inst_get(in);
    if (!added && sdi != nullptr) added = sr.session_dev_add(session, sdi) == SR_OK;
  }
  if (error.empty() && sr.input_end(in) != SR_OK) error = "libsigrok could not read the file";
  sr.string_free(buffer, TRUE);
  sr.session_destroy(session);
  return error;
}

}  // namespace

std::string read_logic_file(const std::string& path, LogicSink& sink, double sample_rate) {
  std::string error;
  const SigrokLibrary* library = sigrok_library(error);
  if (library == nullptr) return error;
  const SigrokLibrary& sr = *library;
  Context context(sr);
  if (context.ctx == nullptr) return "libsigrok did not start";
  Feed feed(sr, sink);
  feed.given_rate = sample_rate;
  sr_session* session = nullptr;
  if (sr.session_load(context.ctx, path.c_str(), &session) == SR_OK) {
    error = read_session_file(session, feed);
  } else {
    const sr_input* in = nullptr;
    if (sr.input_scan_file(path.c_str(), &in) != SR_OK || in == nullptr) {
      return "not a sigrok session or a logic recording libsigrok reads";
    }
    error = read_with_input(path, in, context.ctx, feed);
    sr.input_free(in);
  }
  if (error.empty() && !feed.begun) error = "the recording holds no logic samples";
  return error;
}

}  // namespace pvtap::analyzer
