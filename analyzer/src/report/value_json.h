// Register values as JSON objects, as jsonl lines, the summary and MQTT write them.
#pragma once

#include "formatting/json_writer.h"
#include "report/frame_findings.h"

namespace pvtap::analyzer {

// {"register":"0x1006","name":"battery voltage","value":52.3,"unit":"V"}, with "text" for
// readings that are more than a number and "warnings" when the decoder had doubts.
void write_value_json(JsonWriter& w, const DecodedValue& v, Dialect d);
// The same in parts, so that what depends only on the register is rendered once: the head
// opens the object and ends at the key of "value"; the unit is the member "unit" or nothing;
// the tail closes the object.
void write_value_head(JsonWriter& w, const DecodedValue& v, Dialect d);
void write_value_reading(JsonWriter& w, const DecodedValue& v);
void write_value_unit(JsonWriter& w, const DecodedValue& v);
void write_value_tail(JsonWriter& w, const DecodedValue& v);
// What follows a kept head: the reading, the kept unit member (`,"unit":"V"` or empty) and
// the tail, for ValueJsonCache; the head is in `out` already.
void write_value_rest(std::string& out, std::string_view unit_member, const DecodedValue& v);

// A station's newest value; one no map names with its function and table:
// {"register":"0x0836","name":null,"function":3,"table":"holding","key":"reg_0x0836",
// "value":17357}.
void write_latest_value_json(JsonWriter& w, const LatestValue& v);

// {"table":"holding","function":3,"start":"0x0836","count":80,"replies":172,"values":[
// {"register":"0x0836","key":"reg_0x0836","type":"float32","words":2,"word_order":"high_first",
// "constant":false,"counter":false,"confidence":0.99,"min":..,"max":..,"last":..,
// "evidence":"...","hint":"..."},...]}
void write_inferred_block_json(JsonWriter& w, const InferredBlock& b);

}  // namespace pvtap::analyzer
