// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <Eigen/LU>

#include "freeform_inspection/types.h"

namespace freeform_inspection {

bool isRigidTransform(const Eigen::Matrix4d& T, double tolerance) {
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  return T.topRows<3>().allFinite() &&
         (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < tolerance &&
         R.determinant() > 0.0;
}

}  // namespace freeform_inspection
