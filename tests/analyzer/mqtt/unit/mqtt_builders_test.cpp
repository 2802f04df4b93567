// The pure parts of --mqtt: URLs, topic levels, the event queue's bound, sensor classes.
#include <gtest/gtest.h>

#include "broker/mqtt_outbox.h"
#include "broker/mqtt_url.h"
#include "mqtt/bus_health.h"
#include "mqtt/ha_discovery.h"
#include "mqtt/mqtt_topics.h"

namespace pvtap::analyzer {
namespace {

TEST(MqttUrl, DefaultsThePortBySchemeAndReadsBracketedIpv6) {
  std::string error;
  const auto plain = parse_mqtt_url("mqtt://broker.lan", error);
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->host, "broker.lan");
  EXPECT_EQ(plain->port, 1883);
  EXPECT_FALSE(plain->tls);
  const auto tls = parse_mqtt_url("mqtts://broker.lan/", error);
  ASSERT_TRUE(tls);
  EXPECT_EQ(tls->port, 8883);
  EXPECT_TRUE(tls->tls);
  const auto v6 = parse_mqtt_url("mqtt://[::1]:1884", error);
  ASSERT_TRUE(v6);
  EXPECT_EQ(v6->host, "::1");
  EXPECT_EQ(v6->port, 1884);
}

TEST(MqttUrl, RefusesOtherSchemesAndBadPortsWithAReason) {
  for (const char* bad : {"http://broker", "broker:1883", "mqtt://", "mqtt://h:0", "mqtt://h:65536",
                          "mqtt://h:12x", "mqtt://user@h", "mqtt://[::1"}) {
    std::string error;
    EXPECT_FALSE(parse_mqtt_url(bad, error)) << bad;
    EXPECT_NE(error.find("--mqtt"), std::string::npos) << bad;
  }
}

TEST(MqttTopics, LevelsAreSafeForTopicsAndHomeAssistantIds) {
  EXPECT_EQ(topic_level("/dev/ttyUSB0"), "dev_ttyUSB0");
  EXPECT_EQ(topic_level("192.168.1.5:4001"), "192_168_1_5_4001");
  EXPECT_EQ(topic_level("a+b#c"), "a_b_c");
  const MqttTopics t("pvtap/site", "/dev/ttyUSB0");
  // The run's one serial tap is "bus" whatever its device; another bus is its name.
  EXPECT_EQ(t.bus_level("/dev/ttyUSB0"), "bus");
  EXPECT_EQ(t.bus_level("/dev/ttyUSB1"), "dev_ttyUSB1");
  EXPECT_EQ(t.bus_level("10.0.0.2:4001"), "10_0_0_2_4001");
  EXPECT_EQ(t.bus_level(""), "bus");
  EXPECT_EQ(t.value("bus", 3, "battery_voltage"), "pvtap/site/bus/3/battery_voltage");
  EXPECT_EQ(t.state("bus", 3), "pvtap/site/bus/3/state");
  EXPECT_EQ(t.events("dev_ttyUSB1"), "pvtap/site/dev_ttyUSB1/events");
  EXPECT_EQ(t.status(), "pvtap/site/status");
}

TEST(MqttEventQueue, DropsTheOldestBeyondItsBoundAndCountsThem) {
  MqttEventQueue q(3);
  for (int i = 0; i < 5; ++i) q.push({"t", std::to_string(i)});
  EXPECT_EQ(q.size(), 3u);
  EXPECT_EQ(q.dropped(), 2u);
  EXPECT_EQ(q.front().payload, "2");
  q.pop();
  EXPECT_EQ(q.front().payload, "3");
}

TEST(HaDiscovery, EnergyCountersAreTotalIncreasing) {
  EXPECT_EQ(sensor_class_of("kWh").device_class, "energy");
  EXPECT_EQ(sensor_class_of("kWh").state_class, "total_increasing");
  EXPECT_EQ(sensor_class_of("Wh").state_class, "total_increasing");
  EXPECT_EQ(sensor_class_of("V").device_class, "voltage");
  EXPECT_EQ(sensor_class_of("V").state_class, "measurement");
  EXPECT_EQ(sensor_class_of("mV/°C/2V").device_class, "");
}

TEST(BusHealth, JsonHasEveryFieldDiscoveryNames) {
  BusHealth h;
  for (int i = 0; i < 7; ++i) h.count(SessionFrame{});
  std::string json;
  append_health_json(json, h, HealthContext{});
  for (const HealthField& f : kHealthFields) {
    std::string member = "\"";
    member += f.key;
    member += "\":";
    EXPECT_NE(json.find(member), std::string::npos) << f.key;
  }
  EXPECT_NE(json.find("\"frames\":7"), std::string::npos);
  EXPECT_NE(json.find("\"line_errors\":null"), std::string::npos);
}

TEST(BusHealth, SharingIsTheSessions) {
  HealthContext c;
  c.sharing = BusSharing{2, 5, 4, 0};
  std::string json;
  append_health_json(json, BusHealth{}, c);
  EXPECT_NE(json.find("\"masters\":2,\"collisions\":5,\"lost_in_collision\":4,\"echoes\":0"),
            std::string::npos)
      << json;
}

}  // namespace
}  // namespace pvtap::analyzer
