// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// rostest client of ~inspect_action: a verdict with stage feedback, ABORTED for input that cannot
// be inspected, PREEMPTED on cancel (after the running stage, with nothing published) and on a
// newer goal, which then runs.
#include <algorithm>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "rostest_helpers.h"
#include <actionlib/client/simple_action_client.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>

#include <freeform_inspection/InspectAction.h>
#include <freeform_inspection/InspectionReport.h>

namespace {

using freeform_inspection::InspectAction;
using freeform_inspection::InspectFeedback;
using freeform_inspection::InspectGoal;
using freeform_inspection::InspectionReport;
using freeform_inspection::InspectResult;
using State = actionlib::SimpleClientGoalState;
using Client = actionlib::SimpleActionClient<InspectAction>;
using namespace freeform_inspection_rostest;  // NOLINT(google-build-using-namespace): test helpers

// The feedback of one goal, as it arrives on the client's spinner threads. The entries are
// shared with the client's callback: a feedback message may be handled after the result (they
// come on separate topics), when the test that owned this log has returned.
class FeedbackLog {
 public:
  void add(const InspectFeedback& feedback) { entries_->add(feedback); }
  bool seen(const std::string& stage) const {
    std::lock_guard<std::mutex> lock(entries_->mutex);
    return std::find(entries_->stages.begin(), entries_->stages.end(), stage) !=
           entries_->stages.end();
  }
  std::set<std::string> distinctStages() const {
    std::lock_guard<std::mutex> lock(entries_->mutex);
    return {entries_->stages.begin(), entries_->stages.end()};
  }
  std::vector<float> progress() const {
    std::lock_guard<std::mutex> lock(entries_->mutex);
    return entries_->progress;
  }
  /// For a callback that may outlive this log.
  std::function<void(const InspectFeedback&)> recorder() const {
    return [entries = entries_](const InspectFeedback& feedback) { entries->add(feedback); };
  }

 private:
  struct Entries {
    void add(const InspectFeedback& feedback) {
      std::lock_guard<std::mutex> lock(mutex);
      stages.push_back(feedback.stage);
      progress.push_back(feedback.progress);
    }
    std::mutex mutex;
    std::vector<std::string> stages;
    std::vector<float> progress;
  };
  std::shared_ptr<Entries> entries_ = std::make_shared<Entries>();
};

InspectGoal goalFor(const sensor_msgs::PointCloud2& cloud, const std::string& part_id) {
  const auto request = cloudRequest(cloud, part_id);
  InspectGoal goal;
  goal.part_id = request.part_id;
  goal.use_last_scan = request.use_last_scan;
  goal.cloud = request.cloud;
  goal.tolerance_upper = request.tolerance_upper;
  goal.tolerance_lower = request.tolerance_lower;
  return goal;
}

void send(Client* client, const InspectGoal& goal, FeedbackLog* log) {
  client->sendGoal(
      goal,
      Client::SimpleDoneCallback(),
      Client::SimpleActiveCallback(),
      [record = log->recorder()](const freeform_inspection::InspectFeedbackConstPtr& feedback) {
        record(*feedback);
      });
}

std::string stagesText(const FeedbackLog& log) {
  std::string text;
  for (const auto& stage : log.distinctStages()) {
    text += stage + " ";
  }
  return text;
}

TEST(InspectAction, SampleScanPassesWithThePoseAndStageFeedback) {
  Client client(nodeName() + "/inspect_action", /*spin_thread=*/false);  // main() spins
  ASSERT_TRUE(client.waitForServer(kWait))
      << "no action server " << nodeName() << "/inspect_action";
  FeedbackLog log;
  send(&client, goalFor(sampleCloud(), "action-0001"), &log);
  ASSERT_TRUE(client.waitForResult(kInspectWait));
  EXPECT_EQ(client.getState(), State::SUCCEEDED) << client.getState().getText();
  const auto result = client.getResult();
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, InspectResult::PASS) << result->message;
  EXPECT_EQ(result->report.status, result->status);
  EXPECT_EQ(result->report.registration_status, "ok") << result->message;
  EXPECT_EQ(result->report.part_id, "action-0001");
  EXPECT_EQ(result->report.transform.header.frame_id, "scanner");
  EXPECT_EQ(result->report.transform.child_frame_id, "part");
  expectSamplePose(tf2::transformToEigen(result->report.transform), "action result transform");
  // Feedback and result travel on different topics: the early stages were sent seconds before
  // the result, the last one may still be on its way.
  EXPECT_TRUE(waitUntil([&] { return log.distinctStages().size() >= 2; }, ros::Duration(5.0)))
      << "stages received: " << stagesText(log);
  EXPECT_TRUE(log.seen("inspecting")) << "stages received: " << stagesText(log);
  const std::vector<float> progress = log.progress();
  EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end())) << "progress went backwards";
  for (const float p : progress) {
    EXPECT_GE(p, 0.0F);
    EXPECT_LE(p, 1.0F);
  }
}

TEST(InspectAction, EmptyCloudIsAbortedWithTheReason) {
  Client client(nodeName() + "/inspect_action", false);
  ASSERT_TRUE(client.waitForServer(kWait));
  FeedbackLog log;
  send(&client, goalFor(toCloud({}, "scanner"), "empty"), &log);
  ASSERT_TRUE(client.waitForResult(kWait));
  EXPECT_EQ(client.getState(), State::ABORTED) << client.getState().getText();
  ASSERT_TRUE(client.getResult());
  EXPECT_EQ(client.getResult()->status, InspectResult::ERROR);
  EXPECT_EQ(client.getResult()->report.error_code, "INVALID_INPUT");
  EXPECT_NE(client.getState().getText().find("no finite points"), std::string::npos)
      << client.getState().getText();
}

// The goal's initial_guess reaches the node: a guess without a rotation is refused by name
// (were it dropped, the scan would be searched and pass).
TEST(InspectAction, InitialGuessTravelsWithTheGoal) {
  Client client(nodeName() + "/inspect_action", false);
  ASSERT_TRUE(client.waitForServer(kWait));
  FeedbackLog log;
  InspectGoal goal = goalFor(sampleCloud(), "guess");
  goal.initial_guess.header.frame_id = "scanner";  // rotation left all zero
  send(&client, goal, &log);
  ASSERT_TRUE(client.waitForResult(kInspectWait));
  EXPECT_EQ(client.getState(), State::ABORTED) << client.getState().getText();
  ASSERT_TRUE(client.getResult());
  EXPECT_EQ(client.getResult()->report.error_code, "INVALID_INPUT");
  EXPECT_NE(client.getState().getText().find("initial_guess"), std::string::npos)
      << client.getState().getText();
}

// The goal's alignment reaches the node too: ALIGN_FIXED without a guess is refused naming it.
TEST(InspectAction, AlignmentTravelsWithTheGoal) {
  Client client(nodeName() + "/inspect_action", false);
  ASSERT_TRUE(client.waitForServer(kWait));
  FeedbackLog log;
  InspectGoal goal = goalFor(sampleCloud(), "fixed");
  goal.alignment = InspectGoal::ALIGN_FIXED;
  send(&client, goal, &log);
  ASSERT_TRUE(client.waitForResult(kInspectWait));
  EXPECT_EQ(client.getState(), State::ABORTED) << client.getState().getText();
  ASSERT_TRUE(client.getResult());
  EXPECT_EQ(client.getResult()->report.error_code, "INVALID_INPUT");
  EXPECT_NE(client.getState().getText().find("ALIGN_FIXED"), std::string::npos)
      << client.getState().getText();
}

TEST(InspectAction, CancelDuringTheInspectionEndsPreemptedWhenTheStageEndsAndPublishesNothing) {
  Client client(nodeName() + "/inspect_action", false);
  ASSERT_TRUE(client.waitForServer(kWait));
  FeedbackLog log;
  send(&client, goalFor(sampleCloud(), "cancelled-part"), &log);
  ASSERT_TRUE(waitUntil([&] { return log.seen("inspecting"); }, kWait))
      << "stages received: " << stagesText(log);
  client.cancelGoal();
  // The core checks for a cancel between its stages: the goal ends when the running one ends.
  ASSERT_TRUE(client.waitForResult(kInspectWait));
  EXPECT_EQ(client.getState(), State::PREEMPTED) << client.getState().getText();
  const auto result = client.getResult();
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, InspectResult::ERROR);
  EXPECT_EQ(result->report.error_code, "CANCELLED");
  EXPECT_EQ(result->report.part_id, "cancelled-part");
  EXPECT_NE(result->message.find("inspecting"), std::string::npos) << result->message;
  EXPECT_FALSE(log.seen("publishing"));
  // Nothing of the cancelled run was published: the latched report is an earlier one, if any.
  const auto latest =
      ros::topic::waitForMessage<InspectionReport>(nodeName() + "/result", ros::Duration(2.0));
  if (latest) {
    EXPECT_NE(latest->part_id, "cancelled-part");
  }
}

TEST(InspectAction, ANewerGoalPreemptsTheRunningOneAndThenRuns) {
  Client first(nodeName() + "/inspect_action", false);
  Client second(nodeName() + "/inspect_action", false);
  ASSERT_TRUE(first.waitForServer(kWait));
  ASSERT_TRUE(second.waitForServer(kWait));
  const sensor_msgs::PointCloud2 cloud = sampleCloud();
  FeedbackLog first_log;
  FeedbackLog second_log;
  send(&first, goalFor(cloud, "first"), &first_log);
  ASSERT_TRUE(waitUntil([&] { return first_log.seen("inspecting"); }, kWait));
  send(&second, goalFor(cloud, "second"), &second_log);
  ASSERT_TRUE(first.waitForResult(kInspectWait));
  EXPECT_EQ(first.getState(), State::PREEMPTED) << first.getState().getText();
  ASSERT_TRUE(first.getResult());
  EXPECT_EQ(first.getResult()->report.error_code, "CANCELLED");
  EXPECT_NE(first.getResult()->message.find("newer goal"), std::string::npos)
      << first.getResult()->message;
  ASSERT_TRUE(second.waitForResult(kInspectWait));
  EXPECT_EQ(second.getState(), State::SUCCEEDED) << second.getState().getText();
  ASSERT_TRUE(second.getResult());
  EXPECT_EQ(second.getResult()->status, InspectResult::PASS) << second.getResult()->message;
  EXPECT_EQ(second.getResult()->report.part_id, "second");
}

}  // namespace
