// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// The ~inspect_action server of InspectionNode: the Inspect service with stage feedback and
// cancel. A cancel is honoured between stages, including the core's own stages inside
// "inspecting" (clean, descriptors, features, ..., deviation; see docs/ros.md).
#include <chrono>
#include <functional>
#include <future>
#include <string>
#include <utility>

#include "conversions.h"
#include "inspection_node.h"
#include <ros/callback_queue_interface.h>

namespace freeform_inspection_ros {
namespace {

using freeform_inspection::Inspect;
using freeform_inspection::InspectionReport;

// How often a queued goal looks for a cancel while another inspection runs.
constexpr std::chrono::milliseconds kQueuedPollPeriod(100);

// Runs `read` on the thread that spins the queue it is added to, and hands the answer back.
class QueueRead : public ros::CallbackInterface {
 public:
  explicit QueueRead(std::function<bool()> read) : read_(std::move(read)) {}
  CallResult call() override {
    answer_.set_value(read_());
    return Success;
  }
  std::future<bool> answer() { return answer_.get_future(); }

 private:
  std::function<bool()> read_;
  std::promise<bool> answer_;
};

// actionlib's SimpleActionServer::isPreemptRequested() and isNewGoalAvailable() read flags
// without the server's lock, while its goal and cancel callbacks write them under that lock: a
// data race that ThreadSanitizer reports (docs/soak_and_tsan.md). Those callbacks all run on the
// action queue's one spinner thread, so the flag is read there, in order with every write.
// `stopped` when that thread no longer answers because the node is shutting down.
bool readOnQueue(ros::CallbackQueue* queue,
                 std::function<bool()> read,
                 const std::function<bool()>& shutting_down,
                 bool stopped) {
  const auto probe = boost::make_shared<QueueRead>(std::move(read));
  std::future<bool> answer = probe->answer();
  queue->addCallback(probe);
  while (answer.wait_for(kQueuedPollPeriod) != std::future_status::ready) {
    if (shutting_down()) {
      return stopped;
    }
  }
  return answer.get();
}

Inspect::Request toRequest(const freeform_inspection::InspectGoal& goal) {
  Inspect::Request request;
  request.model_id = goal.model_id;
  request.part_id = goal.part_id;
  request.use_last_scan = goal.use_last_scan;
  request.cloud = goal.cloud;
  request.mesh = goal.mesh;
  request.tolerance_upper = goal.tolerance_upper;
  request.tolerance_lower = goal.tolerance_lower;
  request.initial_guess = goal.initial_guess;
  request.alignment = goal.alignment;
  return request;
}

}  // namespace

void InspectionNode::startActionServer() {
  ros::NodeHandle action_nh(pnh_);
  action_nh.setCallbackQueue(&action_queue_);
  action_server_ = std::make_unique<InspectServer>(
      action_nh,
      "inspect_action",
      [this](const freeform_inspection::InspectGoalConstPtr& goal) { onInspectAction(goal); },
      /*auto_start=*/false);
  action_server_->start();
  action_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &action_queue_);
  action_spinner_->start();
}

void InspectionNode::onInspectAction(const freeform_inspection::InspectGoalConstPtr& goal) {
  std::unique_lock<std::timed_mutex> turn(inspect_mutex_, std::defer_lock);
  if (!actionStage("received", 0.0) || !waitForTurn(&turn)) {
    InspectionReport report =
        cancelledReport("while waiting for the running inspection",
                        goal->mesh.polygons.empty() ? goal->cloud.header : goal->mesh.header);
    report.part_id = goal->part_id;
    finishAction(report);
    return;
  }
  finishAction(inspectAndPublishLocked(
      toRequest(*goal),
      [this](const std::string& stage, double progress) { return actionStage(stage, progress); }));
}

bool InspectionNode::waitForTurn(std::unique_lock<std::timed_mutex>* turn) {
  while (!turn->try_lock_for(kQueuedPollPeriod)) {
    if (!actionStage("queued", 0.0)) {
      return false;
    }
  }
  return true;
}

bool InspectionNode::actionStage(const std::string& stage, double progress) {
  const auto shutting_down = [this] { return stopping(); };
  const auto preempted = [this] { return action_server_->isPreemptRequested(); };
  if (shutting_down() || readOnQueue(&action_queue_, preempted, shutting_down, true)) {
    return false;
  }
  freeform_inspection::InspectFeedback feedback;
  feedback.stage = stage;
  feedback.progress = static_cast<float>(progress);
  action_server_->publishFeedback(feedback);
  return true;
}

void InspectionNode::finishAction(const InspectionReport& report) {
  freeform_inspection::InspectResult result;
  result.report = report;
  const auto shutting_down = [this] { return stopping(); };
  const auto newer_goal = [this] { return action_server_->isNewGoalAvailable(); };
  if (report.error_code == kCancelledCode &&
      readOnQueue(&action_queue_, newer_goal, shutting_down, false)) {
    result.report.message = "preempted by a newer goal: " + report.message;
  }
  result.status = result.report.status;
  result.message = result.report.message;
  if (report.error_code == kCancelledCode) {
    ROS_INFO_STREAM("~inspect_action: " << result.message);
    action_server_->setPreempted(result, result.message);
  } else if (report.status == InspectionReport::ERROR) {
    action_server_->setAborted(result, result.message);  // nothing to judge: the reason is in it
  } else {
    action_server_->setSucceeded(result, result.message);
  }
}

}  // namespace freeform_inspection_ros
