// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// A compressor blade, 140 mm long on a 70 x 28 x 16 mm root block (OpenSCAD, millimetres): a
// cambered profile 60 mm wide, twisted by 35 degrees and tapered to 75 % towards the tip.
$fn = 48;
module profile() {
  polygon([for (i = [0:40]) let(x = i / 40) [60 * x - 20, 18 * sqrt(x) * (1 - x) + 2 * x],
           for (i = [40:-1:0]) let(x = i / 40) [60 * x - 20, -6 * sqrt(x) * (1 - x) + 2 * x]]);
}
union() {
  linear_extrude(height = 140, twist = 35, scale = 0.75, slices = 60) profile();
  translate([-28, -14, -16]) cube([70, 28, 16]);
}
