// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
// A cast pump cover, a 120 mm disc 12 mm thick (OpenSCAD, millimetres): a bored boss off the
// centre, a second small boss, four bolt holes unevenly spaced and a pocket. Nearly a disc: what
// tells its turns apart is a few per cent of its surface.
$fn = 64;
difference() {
  union() {
    cylinder(d = 120, h = 12);
    translate([18, 8, 0]) cylinder(d = 44, h = 30);
    translate([-30, -25, 0]) cylinder(d = 18, h = 20);
  }
  translate([18, 8, -1]) cylinder(d = 22, h = 40);
  for (a = [0, 100, 200, 290]) rotate([0, 0, a]) translate([48, 0, -1]) cylinder(d = 9, h = 20);
  translate([-40, 20, 6]) cube([25, 12, 10]);
}
