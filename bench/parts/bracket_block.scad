// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// A machined L-block, 80 x 50 x 45 mm (OpenSCAD, millimetres): a base plate and an upright,
// a counterbored bore off the middle, a cross hole through the upright, a rib, a notch and a
// chamfered corner. Flat faces and sharp edges, no symmetry.
$fn = 48;
difference() {
  union() {
    cube([80, 50, 15]);
    cube([20, 50, 45]);
    translate([20, 0, 15]) cube([12, 8, 20]);
  }
  translate([52, 25, -1]) cylinder(d = 16, h = 20);
  translate([52, 25, 10]) cylinder(d = 26, h = 10);
  translate([-1, 15, 30]) rotate([0, 90, 0]) cylinder(d = 10, h = 30);
  translate([60, -1, -1]) cube([8, 12, 20]);
  translate([80, 50, 7]) rotate([0, 0, 45]) cube([10, 10, 20], center = true);
}
