// The items that link a request and its reply: frames, response time and what the match found.
#pragma once

#include <string>

#include "plan/frame_record.h"
#include "tree/tree_builder.h"

namespace pvtap::dissector {

// Why a request got no reply, and the request that came first where that was the reason.
std::string unanswered_text(const FrameRecord& r, const DescriptionContext& ctx);

// The links of a request or a reply to its partner, and the expert infos of the match.
void add_matching(Builder& b, const FrameRecord& r);

}  // namespace pvtap::dissector
