// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "blade_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "freeform_inspection/mesh.h"

namespace freeform_inspection {
namespace tools {
namespace {

constexpr double kPi = 3.14159265358979323846;

double degToRad(double degrees) {
  return degrees * kPi / 180.0;
}

double lerp(double a, double b, double t) {
  return a + (b - a) * t;
}

double smoothstep(double t) {
  return t * t * (3.0 - 2.0 * t);
}

// Chord stations in [0, 1]: a blend of cosine spacing (fine at the round leading edge and at the
// trailing edge rounding) and uniform spacing (even triangles elsewhere).
std::vector<double> chordStations(int count, double clustering) {
  std::vector<double> stations(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(count - 1);
    const double cosine = 0.5 * (1.0 - std::cos(kPi * s));
    stations[static_cast<std::size_t>(i)] = lerp(s, cosine, clustering);
  }
  stations.back() = 1.0;  // exact, so the trailing edge rounding closes to zero thickness
  return stations;
}

// Index of a point within a section: lower side first, so the outline runs counter-clockwise
// seen from +z (outward wall normals with the quad order used below).
int lowerIndex(int station) {
  return station;
}
int upperIndex(int station, int stations) {
  return station == 0 ? 0 : 2 * (stations - 1) - station;
}

// Lower and upper y at each station, on a shared x; assembled into layout order.
std::vector<Eigen::Vector2d> assembleOutline(const std::vector<double>& x,
                                             const std::vector<double>& y_lower,
                                             const std::vector<double>& y_upper) {
  const int n = static_cast<int>(x.size());
  std::vector<Eigen::Vector2d> outline(static_cast<std::size_t>(2 * (n - 1)));
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    outline[static_cast<std::size_t>(lowerIndex(i))] = Eigen::Vector2d(x[k], y_lower[k]);
    outline[static_cast<std::size_t>(upperIndex(i, n))] = Eigen::Vector2d(x[k], y_upper[k]);
  }
  return outline;
}

double nacaCamber(double x, double m, double p) {
  if (x < p) {
    return m / (p * p) * (2.0 * p * x - x * x);
  }
  return m / ((1.0 - p) * (1.0 - p)) * ((1.0 - 2.0 * p) + 2.0 * p * x - x * x);
}

double nacaHalfThickness(double x, double t) {
  return 5.0 * t *
         (0.2969 * std::sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x -
          0.1015 * x * x * x * x);
}

// Half thickness [chord fraction]: NACA distribution tilted so that it ends at half the trailing
// edge thickness, then closed by a quarter ellipse one thickness long, so the trailing edge is
// round and shared by both sides instead of a knife edge or an open gap.
double halfThickness(double x, double t, double te_half) {
  const double base = nacaHalfThickness(x, t) + x * (te_half - nacaHalfThickness(1.0, t));
  const double rounding = 2.0 * te_half;
  const double u = (x - (1.0 - rounding)) / rounding;
  return u <= 0.0 ? base : base * std::sqrt(std::max(0.0, 1.0 - u * u));
}

struct AirfoilShape {
  double chord_mm;
  double max_camber;
  double max_thickness;
  double stagger_rad;
  Eigen::Vector2d stacking_point;  // [mm]
};

AirfoilShape airfoilAt(const BladeParameters& p, double span_fraction) {
  const double eta = span_fraction;
  AirfoilShape shape;
  shape.chord_mm = lerp(p.root_chord_mm, p.tip_chord_mm, eta);
  shape.max_camber = lerp(p.root_max_camber, p.tip_max_camber, eta);
  shape.max_thickness = lerp(p.root_max_thickness, p.tip_max_thickness, eta);
  shape.stagger_rad = degToRad(lerp(p.root_stagger_deg, p.tip_stagger_deg, eta));
  shape.stacking_point = eta * eta * Eigen::Vector2d(p.tip_sweep_mm, p.tip_lean_mm);
  return shape;
}

// Thickness is added normal to the chord, not to the camber line as in the original NACA
// construction, so both sides share the chord stations: the section stays x-monotone in its
// chord frame, which is what makes the strip caps valid.
std::vector<Eigen::Vector2d> airfoilOutline(const BladeParameters& p, const AirfoilShape& shape) {
  const std::vector<double> xi = chordStations(p.chord_stations, p.leading_edge_clustering);
  const double c = shape.chord_mm;
  const double te_half = 0.5 * p.trailing_edge_thickness_mm / c;
  std::vector<double> x(xi.size()), y_lower(xi.size()), y_upper(xi.size());
  for (std::size_t i = 0; i < xi.size(); ++i) {
    const double yc = nacaCamber(xi[i], shape.max_camber, p.camber_position);
    const double yt = halfThickness(xi[i], shape.max_thickness, te_half);
    x[i] = c * (xi[i] - p.stacking_position);
    y_lower[i] = c * (yc - yt);
    y_upper[i] = c * (yc + yt);
  }
  std::vector<Eigen::Vector2d> outline = assembleOutline(x, y_lower, y_upper);
  const Eigen::Rotation2Dd stagger(shape.stagger_rad);
  for (auto& point : outline) {
    point = stagger * point + shape.stacking_point;
  }
  return outline;
}

// Platform stations are uniform: cosine spacing would put the first station so close to the flat
// superellipse end that the end triangle of the cap becomes a sliver.
std::vector<Eigen::Vector2d> platformOutline(const BladeParameters& p) {
  const std::vector<double> xi = chordStations(p.chord_stations, 0.0);
  const double a = 0.5 * p.platform_length_mm;
  const double b = 0.5 * p.platform_width_mm;
  const double e = p.platform_exponent;
  std::vector<double> x(xi.size()), y_lower(xi.size()), y_upper(xi.size());
  for (std::size_t i = 0; i < xi.size(); ++i) {
    x[i] = a * (2.0 * xi[i] - 1.0);
    const double r = std::max(0.0, 1.0 - std::pow(std::abs(x[i] / a), e));
    y_upper[i] = b * std::pow(r, 1.0 / e);
    y_lower[i] = -y_upper[i];
  }
  std::vector<Eigen::Vector2d> outline = assembleOutline(x, y_lower, y_upper);
  const Eigen::Rotation2Dd rotation(degToRad(p.platform_angle_deg));
  const Eigen::Vector2d offset(p.platform_offset_x_mm, p.platform_offset_y_mm);
  for (auto& point : outline) {
    point = rotation * point + offset;
  }
  return outline;
}

std::vector<Eigen::Vector2d> blendOutlines(const std::vector<Eigen::Vector2d>& from,
                                           const std::vector<Eigen::Vector2d>& to,
                                           double weight) {
  std::vector<Eigen::Vector2d> blend(from.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    blend[i] = (1.0 - weight) * from[i] + weight * to[i];
  }
  return blend;
}

void appendEvenly(std::vector<double>& z, double from, double to, int intervals) {
  for (int k = 1; k <= intervals; ++k) {
    z.push_back(lerp(from, to, static_cast<double>(k) / static_cast<double>(intervals)));
  }
}

// Splits the quad a-b-c-d (counter-clockwise seen from outside) along its shorter diagonal,
// which keeps the smallest angles of sheared (twisted) quads larger.
void addQuad(TriangleMesh& mesh, int a, int b, int c, int d) {
  const auto& v = mesh.vertices;
  const auto at = [&v](int i) { return v[static_cast<std::size_t>(i)]; };
  if ((at(a) - at(c)).squaredNorm() <= (at(b) - at(d)).squaredNorm()) {
    mesh.faces.emplace_back(a, b, c);
    mesh.faces.emplace_back(a, c, d);
  } else {
    mesh.faces.emplace_back(a, b, d);
    mesh.faces.emplace_back(b, c, d);
  }
}

void addWalls(TriangleMesh& mesh, int sections, int m) {
  for (int k = 0; k + 1 < sections; ++k) {
    for (int j = 0; j < m; ++j) {
      const int next = (j + 1) % m;
      addQuad(mesh, k * m + j, k * m + next, (k + 1) * m + next, (k + 1) * m + j);
    }
  }
}

// Points of a cap along one chord station, from the lower to the upper side: the section points
// plus `rows` - 1 evenly spaced interior points (appended to the mesh).
std::vector<int> capColumn(TriangleMesh& mesh, int lower, int upper, int rows) {
  const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(lower)];
  const Eigen::Vector3d b = mesh.vertices[static_cast<std::size_t>(upper)];
  std::vector<int> column{lower};
  for (int r = 1; r < rows; ++r) {
    column.push_back(static_cast<int>(mesh.vertices.size()));
    mesh.vertices.push_back(a + (b - a) * (static_cast<double>(r) / static_cast<double>(rows)));
  }
  if (upper != lower) {
    column.push_back(upper);
  }
  return column;
}

// Triangulates the strip between two columns at consecutive chord stations (left has the
// smaller chord coordinate). The strip is a convex trapezoid, so any monotone zipper is valid;
// taking the shorter diagonal at each step keeps the angles large. `up` selects the winding of
// the top cap (normal +z) or the bottom cap (normal -z).
void zipColumns(TriangleMesh& mesh,
                const std::vector<int>& left,
                const std::vector<int>& right,
                bool up) {
  const auto dist = [&mesh](int a, int b) {
    return (mesh.vertices[static_cast<std::size_t>(a)] - mesh.vertices[static_cast<std::size_t>(b)])
        .squaredNorm();
  };
  const auto triangle = [&](int a, int b, int c) {
    if (up) {
      mesh.faces.emplace_back(a, b, c);
    } else {
      mesh.faces.emplace_back(a, c, b);
    }
  };
  std::size_t i = 0;
  std::size_t j = 0;
  while (i + 1 < left.size() || j + 1 < right.size()) {
    const bool advance_left =
        j + 1 == right.size() ||
        (i + 1 < left.size() && dist(left[i + 1], right[j]) < dist(left[i], right[j + 1]));
    if (advance_left) {
      triangle(left[i], right[j], left[i + 1]);
      ++i;
    } else {
      triangle(left[i], right[j], right[j + 1]);
      ++j;
    }
  }
}

// Rows per chord station of a cap: near-square cells (row height about the mean station
// spacing), so the strips of a wide, flat section such as the platform are not cut into long
// slivers; grown by at most kCapRowGrowth per station from the single-point leading and trailing
// edges, so neighbouring columns stay similar and the zipper between them makes no thin fans.
std::vector<int> capRows(const TriangleMesh& mesh, int first, int stations) {
  constexpr int kCapRowGrowth = 2;
  const auto point = [&mesh, first](int i) {
    return mesh.vertices[static_cast<std::size_t>(first + i)];
  };
  const double spacing = (point(lowerIndex(stations - 1)) - point(lowerIndex(0))).norm() /
                         static_cast<double>(stations - 1);
  std::vector<int> rows(static_cast<std::size_t>(stations), 0);
  for (int i = 1; i + 1 < stations; ++i) {
    const double length = (point(upperIndex(i, stations)) - point(lowerIndex(i))).norm();
    rows[static_cast<std::size_t>(i)] =
        std::max(1, static_cast<int>(std::lround(length / spacing)));
  }
  for (std::size_t i = 1; i < rows.size(); ++i) {
    rows[i] = std::min(rows[i], rows[i - 1] + kCapRowGrowth);
  }
  for (std::size_t i = rows.size() - 1; i-- > 0;) {
    rows[i] = std::min(rows[i], rows[i + 1] + kCapRowGrowth);
  }
  return rows;
}

// Closes the section that starts at vertex `first` with strips between its lower and upper
// side at matching chord stations (valid because every section is monotone along its chord).
void addCap(TriangleMesh& mesh, int first, int stations, bool up) {
  const std::vector<int> rows = capRows(mesh, first, stations);
  std::vector<int> previous;
  for (int i = 0; i < stations; ++i) {
    const std::vector<int> column = capColumn(mesh,
                                              first + lowerIndex(i),
                                              first + upperIndex(i, stations),
                                              rows[static_cast<std::size_t>(i)]);
    if (i > 0) {
      zipColumns(mesh, previous, column, up);
    }
    previous = column;
  }
}

Status invalid(const std::string& field, double value) {
  return Status::failure(StatusCode::kInvalidInput,
                         "blade parameter " + field + " out of range: " + std::to_string(value));
}

}  // namespace

BladeParameters fineBladeParameters() {
  BladeParameters p;
  p.chord_stations = 2 * p.chord_stations - 1;
  p.platform_intervals *= 2;
  p.fillet_intervals *= 2;
  p.airfoil_intervals *= 2;
  return p;
}

Status validateBladeParameters(const BladeParameters& p) {
  const std::pair<const char*, double> positive[] = {
      {"span_mm", p.span_mm},
      {"root_chord_mm", p.root_chord_mm},
      {"tip_chord_mm", p.tip_chord_mm},
      {"root_max_thickness", p.root_max_thickness},
      {"tip_max_thickness", p.tip_max_thickness},
      {"trailing_edge_thickness_mm", p.trailing_edge_thickness_mm},
      {"platform_length_mm", p.platform_length_mm},
      {"platform_width_mm", p.platform_width_mm},
      {"platform_exponent", p.platform_exponent},
      {"platform_height_mm", p.platform_height_mm},
      {"fillet_height_mm", p.fillet_height_mm},
  };
  for (const auto& field : positive) {
    if (!(field.second > 0.0) || !std::isfinite(field.second)) {
      return invalid(field.first, field.second);
    }
  }
  if (!(p.camber_position > 0.0 && p.camber_position < 1.0)) {
    return invalid("camber_position", p.camber_position);
  }
  if (!(p.leading_edge_clustering >= 0.0 && p.leading_edge_clustering <= 1.0)) {
    return invalid("leading_edge_clustering", p.leading_edge_clustering);
  }
  if (p.chord_stations < 4) {
    return invalid("chord_stations", p.chord_stations);
  }
  if (p.platform_intervals < 1 || p.fillet_intervals < 1 || p.airfoil_intervals < 1) {
    return invalid("platform/fillet/airfoil_intervals",
                   std::min({p.platform_intervals, p.fillet_intervals, p.airfoil_intervals}));
  }
  return Status::success();
}

BladeLayout bladeLayout(const BladeParameters& p) {
  BladeLayout layout;
  layout.points_per_section = 2 * (p.chord_stations - 1);
  layout.leading_edge_point = lowerIndex(0);
  layout.trailing_edge_point = lowerIndex(p.chord_stations - 1);
  const double z_fillet = p.platform_height_mm;
  const double z_root = z_fillet + p.fillet_height_mm;
  layout.section_z_mm.push_back(0.0);
  appendEvenly(layout.section_z_mm, 0.0, z_fillet, p.platform_intervals);
  appendEvenly(layout.section_z_mm, z_fillet, z_root, p.fillet_intervals);
  layout.root_section = static_cast<int>(layout.section_z_mm.size()) - 1;
  appendEvenly(layout.section_z_mm, z_root, z_root + p.span_mm, p.airfoil_intervals);
  return layout;
}

std::vector<Eigen::Vector2d> sectionOutline(const BladeParameters& p, double z_mm) {
  const double z_fillet = p.platform_height_mm;
  const double z_root = z_fillet + p.fillet_height_mm;
  if (z_mm >= z_root) {
    return airfoilOutline(p, airfoilAt(p, std::min(1.0, (z_mm - z_root) / p.span_mm)));
  }
  if (z_mm <= z_fillet) {
    return platformOutline(p);
  }
  const double weight = smoothstep((z_mm - z_fillet) / p.fillet_height_mm);
  return blendOutlines(platformOutline(p), airfoilOutline(p, airfoilAt(p, 0.0)), weight);
}

TriangleMesh generateBlade(const BladeParameters& p) {
  TriangleMesh mesh;
  if (!validateBladeParameters(p).ok()) {
    return mesh;
  }
  const BladeLayout layout = bladeLayout(p);
  for (const double z : layout.section_z_mm) {
    for (const auto& point : sectionOutline(p, z)) {
      mesh.vertices.emplace_back(point.x(), point.y(), z);
    }
  }
  const int sections = static_cast<int>(layout.section_z_mm.size());
  const int m = layout.points_per_section;
  addWalls(mesh, sections, m);
  addCap(mesh, 0, p.chord_stations, false);
  addCap(mesh, (sections - 1) * m, p.chord_stations, true);
  mesh.face_normals = computeFaceNormals(mesh.vertices, mesh.faces);
  return mesh;
}

}  // namespace tools
}  // namespace freeform_inspection
