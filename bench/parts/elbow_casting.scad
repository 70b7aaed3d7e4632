// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// A cast pipe elbow (OpenSCAD, millimetres): a 90-degree bend of a 36 mm tube with a 26 mm bore
// on a 50 mm radius, a round flange with four bolt holes at one end, a plain flange at the
// other and a boss on the bend. A torus is symmetric about its axis: the flanges and the boss
// are what fix the turn along the bend.
$fn = 48;
difference() {
  union() {
    rotate_extrude(angle = 90) translate([50, 0]) circle(d = 36);
    rotate([90, 0, 0]) translate([50, 0, -4]) cylinder(d = 70, h = 8);
    translate([0, 50, 0]) rotate([0, 90, 0]) translate([0, 0, -3]) cylinder(d = 56, h = 6);
    translate([35, 35, 15]) sphere(d = 22);
  }
  rotate_extrude(angle = 90) translate([50, 0]) circle(d = 26);
  rotate([90, 0, 0]) translate([50, 0, -10]) cylinder(d = 26, h = 20);
  translate([0, 50, 0]) rotate([0, 90, 0]) translate([0, 0, -10]) cylinder(d = 26, h = 20);
  for (a = [45, 135, 225, 315])
    rotate([90, 0, 0]) translate([50 + 27 * cos(a), 27 * sin(a), -10]) cylinder(d = 6, h = 20);
}
