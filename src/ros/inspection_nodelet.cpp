// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <memory>

#include "inspection_node.h"
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

namespace freeform_inspection_ros {

/// InspectionNode as the nodelet `freeform_inspection/InspectionNodelet`: the same class as the
/// standalone node, loaded into a manager so that clouds from a scanner nodelet in the same
/// manager arrive without a copy.
class InspectionNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    node_ = std::make_unique<InspectionNode>(getNodeHandle(), getPrivateNodeHandle());
    if (!node_->ok()) {
      // A nodelet cannot end its manager; it stays loaded and idle, the errors are logged.
      NODELET_FATAL("invalid parameters: this nodelet does not inspect (see the errors above)");
    }
  }

  std::unique_ptr<InspectionNode> node_;
};

}  // namespace freeform_inspection_ros

PLUGINLIB_EXPORT_CLASS(freeform_inspection_ros::InspectionNodelet, nodelet::Nodelet)
