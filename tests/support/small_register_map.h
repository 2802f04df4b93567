// A one-register Hybrid map (battery voltage at 0x1006, 0.1 V), for tests that load a map.
#pragma once

#include <string_view>

namespace pvtap {

inline constexpr std::string_view kSmallRegisterMap = R"toml(dialect = "hybrid"
title = "small"

[[register]]
address = 0x1006
key = "battery_voltage"
name = "battery voltage"
scale = 0.1
unit = "V"
)toml";

}  // namespace pvtap
