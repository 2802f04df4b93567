#include "logic/srzip_writer.h"

#include <zip.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>

namespace pvtap::sim {
namespace {

constexpr std::uint64_t kChunkSamples = 4 << 20;  // libsigrok's srzip output uses 4 MiB chunks

// ChunkSource: the samples [first, first + count) rendered when libzip opens the entry.
struct ChunkSource {
  const LogicSignals* signals = nullptr;
  std::uint64_t first = 0, count = 0;
  unsigned unitsize = 1;
  std::vector<std::uint8_t> data;
  std::size_t read = 0;

  void render() {
    data.assign(count * unitsize, 0);
    for (std::size_t c = 0; c < signals->channels.size(); ++c) {
      const ChannelSignal& ch = signals->channels[c];
      const auto& t = ch.toggles;
      auto it = std::upper_bound(t.begin(), t.end(), first);
      bool level = ch.initial != (((it - t.begin()) & 1) != 0);
      const auto mask = static_cast<std::uint8_t>(1u << (c % 8));
      // Run by run: a long idle stretch costs one fill, not one test per sample.
      std::uint64_t s = 0;
      while (s < count) {
        const std::uint64_t next = it == t.end() ? count : std::min(count, *it - first);
        if (level)
          for (std::uint64_t i = s; i < next; ++i) data[i * unitsize + c / 8] |= mask;
        s = next;
        if (it != t.end() && *it - first == next) {
          level = !level;
          ++it;
        }
      }
    }
  }
};

zip_int64_t chunk_callback(void* state, void* out, zip_uint64_t len, zip_source_cmd_t cmd) {
  auto* chunk = static_cast<ChunkSource*>(state);
  switch (cmd) {
    case ZIP_SOURCE_OPEN:
      chunk->render();
      chunk->read = 0;
      return 0;
    case ZIP_SOURCE_READ: {
      const auto n = std::min<std::size_t>(len, chunk->data.size() - chunk->read);
      std::memcpy(out, chunk->data.data() + chunk->read, n);
      chunk->read += n;
      return static_cast<zip_int64_t>(n);
    }
    case ZIP_SOURCE_CLOSE:
      chunk->data = {};
      return 0;
    case ZIP_SOURCE_STAT: {
      auto* st = static_cast<zip_stat_t*>(out);
      zip_stat_init(st);
      st->size = chunk->count * chunk->unitsize;
      st->valid |= ZIP_STAT_SIZE;
      return sizeof(*st);
    }
    case ZIP_SOURCE_ERROR:
      return zip_error_to_data(nullptr, out, len);
    case ZIP_SOURCE_FREE:
      return 0;
    case ZIP_SOURCE_SUPPORTS:
      return zip_source_make_command_bitmap(ZIP_SOURCE_OPEN, ZIP_SOURCE_READ, ZIP_SOURCE_CLOSE,
                                            ZIP_SOURCE_STAT, ZIP_SOURCE_ERROR, ZIP_SOURCE_FREE, -1);
    default:
      return -1;
  }
}

std::string metadata(const LogicSignals& s, unsigned unitsize) {
  std::ostringstream m;
  m << "[global]\nsigrok version=0.5.2\n\n[device 1]\ncapturefile=logic-1\n"
    << "total probes=" << s.channels.size()
    << "\nsamplerate=" << static_cast<std::uint64_t>(s.sample_rate) << " Hz\ntotal analog=0\n";
  for (std::size_t i = 0; i < s.channels.size(); ++i)
    m << "probe" << i + 1 << "=" << s.channels[i].name << "\n";
  m << "unitsize=" << unitsize << "\n";
  return m.str();
}

// Adds an entry stamped with the session's start, so that one seed gives the same file.
bool add_entry(zip_t* z, const std::string& name, zip_source_t* src, std::int64_t mtime) {
  const zip_int64_t index = src ? zip_file_add(z, name.c_str(), src, ZIP_FL_OVERWRITE) : -1;
  if (index < 0) {
    zip_source_free(src);
    return false;
  }
  return zip_file_set_mtime(z, static_cast<zip_uint64_t>(index), static_cast<time_t>(mtime), 0) ==
         0;
}

}  // namespace

std::string write_srzip(const LogicSignals& s, const std::string& path) {
  const unsigned unitsize = static_cast<unsigned>((s.channels.size() + 7) / 8);
  const std::string version = "2", meta = metadata(s, unitsize);
  // Written beside the target and renamed: nothing half-written is left under its name.
  const std::string partial = path + ".partial";
  int error = 0;
  zip_t* z = zip_open(partial.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!z) return "cannot create the session file";
  const auto text = [&](const std::string& t) {
    return zip_source_buffer(z, t.data(), t.size(), 0);
  };
  bool ok = add_entry(z, "version", text(version), s.start_unix) &&
            add_entry(z, "metadata", text(meta), s.start_unix);
  std::vector<std::unique_ptr<ChunkSource>> chunks;
  for (std::uint64_t first = 0; ok && first < s.samples; first += kChunkSamples) {
    auto chunk = std::make_unique<ChunkSource>(
        ChunkSource{&s, first, std::min(kChunkSamples, s.samples - first), unitsize, {}, 0});
    zip_source_t* src = zip_source_function(z, chunk_callback, chunk.get());
    ok = add_entry(z, "logic-1-" + std::to_string(chunks.size() + 1), src, s.start_unix);
    chunks.push_back(std::move(chunk));
  }
  if (!ok || zip_close(z) != 0) {
    const std::string why = zip_strerror(z);
    zip_discard(z);
    std::remove(partial.c_str());
    return "cannot write the session file: " + why;
  }
  if (std::rename(partial.c_str(), path.c_str()) != 0) return "cannot rename the session file";
  return {};
}

}  // namespace pvtap::sim
