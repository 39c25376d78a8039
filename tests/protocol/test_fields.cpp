// SPDX-License-Identifier: Apache-2.0
// Fields named at compile time (messages.hpp): field_index_of gives the numbers of SPEC.md §10.1
// (written out here from the SPEC's tables, so the test checks the catalogue walk independently),
// and fields_as copies every field between messages that share a field list.
#include <gtest/gtest.h>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/messages.hpp"

namespace palp::proto {
namespace {

TEST(FieldIndex, TheFieldsTheFirmwareRefusesCarryTheSpecTablesNumbers) {
  EXPECT_EQ(field_index_of<&EnterBootloader::magic>(), 0);
  EXPECT_EQ(field_index_of<&SetParams::travel_min_counts>(), 4);
  EXPECT_EQ(field_index_of<&SetParams::heartbeat_timeout_ms>(), 6);
  EXPECT_EQ(field_index_of<&SetParams::control_rate_Hz>(), 7);
  EXPECT_EQ(field_index_of<&Calibration::kf_position_counts>(), 1);
  EXPECT_EQ(field_index_of<&Calibration::kf_N_per_A>(), 2);
  EXPECT_EQ(field_index_of<&LoadRamp::step_A>(), 2);
  EXPECT_EQ(field_index_of<&LoadSine::amplitude_A>(), 1);
  EXPECT_EQ(field_index_of<&LoadSweep::amplitude_A>(), 1);
  EXPECT_EQ(field_index_of<&LoadSweep::stop_Hz>(), 3);
  EXPECT_EQ(field_index_of<&LoadSweep::step_Hz>(), 4);
  EXPECT_EQ(field_index_of<&LoadMultisine::line_last>(), 3);
  EXPECT_EQ(field_index_of<&LoadMultisine::line_amplitude_A>(), 5);
  EXPECT_EQ(field_index_of<&LoadMultisine::phase_mode>(), 6);
  EXPECT_EQ(field_index_of<&StreamConfigure::decimation>(), 1);
  EXPECT_EQ(field_index_of<&StreamConfigure::batch_samples>(), 2);
}

TEST(FieldIndex, CountsArrayAndTextFieldsAsOneFieldEach) {
  // DeviceInfo: three 16-24 byte texts before its last field, state (#15)
  EXPECT_EQ(field_index_of<&DeviceInfo::git_hash>(), 6);
  EXPECT_EQ(field_index_of<&DeviceInfo::serial>(), 8);
  EXPECT_EQ(field_index_of<&DeviceInfo::state>(), 15);
  // Calibration: two bounded and two fixed arrays before its last field (#9)
  EXPECT_EQ(field_index_of<&Calibration::pressure_gain>(), 6);
  EXPECT_EQ(field_index_of<&Calibration::stroke_origin_valid>(), 9);
  EXPECT_EQ(field_index_of<&SampleBatch::data>(), 5);
}

TEST(FieldIndex, NamesTheFieldItsCatalogueEntryDescribes) {
  EXPECT_STREQ(SetParams::kFields[field_index_of<&SetParams::supply_V>()].name, "supply_V");
  EXPECT_STREQ(LoadContactWatch::kFields[field_index_of<&LoadContactWatch::timeout_s>()].name,
               "timeout_s");
  EXPECT_STREQ(Health::kFields[field_index_of<&Health::stream_gaps>()].name, "stream_gaps");
}

TEST(SameFields, HoldsForTheSetRequestsAndTheirRepliesOnly) {
  EXPECT_TRUE((same_fields<SetParams, Params>()));
  EXPECT_TRUE((same_fields<SetCalibration, Calibration>()));
  EXPECT_FALSE((same_fields<Params, Calibration>()));
  // LoadSweep starts with LoadSine's offset_A and amplitude_A, then differs
  EXPECT_FALSE((same_fields<LoadSine, LoadSweep>()));
  // Pong is Ping's fields and one more
  EXPECT_FALSE((same_fields<Ping, Pong>()));
}

TEST(FieldsAs, CopiesEveryFieldOfSetParamsAndSetCalibration) {
  // filled_example sets every field to a distinct non-default value in field order, so a field
  // left out of the copy would keep its default and differ
  for (u32 salt : {1u, 2u, 77u}) {
    EXPECT_EQ(fields_as<Params>(filled_example<SetParams>(salt)), filled_example<Params>(salt));
    EXPECT_EQ(fields_as<SetParams>(filled_example<Params>(salt)), filled_example<SetParams>(salt));
    EXPECT_EQ(fields_as<Calibration>(filled_example<SetCalibration>(salt)),
              filled_example<Calibration>(salt));
  }
  EXPECT_NE(filled_example<Params>(1), Params{});
}

}  // namespace
}  // namespace palp::proto
