// StatusLine: one line on a terminal's stderr, redrawn in place while a live capture runs.
#pragma once

#include <optional>
#include <string>

namespace pvtap::analyzer {

class StatusLine {
 public:
  explicit StatusLine(bool enabled) : enabled_(enabled) {}
  ~StatusLine() { clear(); }
  StatusLine(const StatusLine&) = delete;
  StatusLine& operator=(const StatusLine&) = delete;

  bool due(double now) const { return enabled_ && now >= next_; }
  // When the line is next to be redrawn; nullopt when it is off.
  std::optional<double> next_due() const {
    return enabled_ ? std::optional<double>(next_) : std::nullopt;
  }
  // Draws `text` in place of the previous line (at most a few times a second: see due()).
  void show(double now, const std::string& text);
  // Erases the line, e.g. before other output goes to the same terminal.
  void clear();

 private:
  bool enabled_;
  bool shown_ = false;
  double next_ = 0;
};

}  // namespace pvtap::analyzer
