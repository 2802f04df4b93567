#include "writers/pdu_capture_output.h"

namespace pvtap::analyzer {

bool PduCaptureOutput::open(const std::string& path, bool flush_each_record, const RunFacts& run) {
  run_ = run;
  if (!file_.open(path)) return false;
  file_.flush_each_record(flush_each_record);
  return true;
}

bool PduCaptureOutput::close() {
  return file_.close();
}

}  // namespace pvtap::analyzer
