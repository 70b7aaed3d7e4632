// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include "report_html.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "deviation_views.h"
#include "file_output.h"
#include "histogram_svg.h"
#include "html_util.h"

namespace freeform_inspection {
namespace {

// Inline so the file stays self-contained; print rules keep the banner colours on paper.
constexpr char kStyle[] = R"(<style>
body{font-family:sans-serif;margin:24px auto;max-width:1500px;color:#222}
h1{font-size:20px;margin:0 0 12px}h2{font-size:16px;margin:24px 0 8px;border-bottom:1px solid #ccc}
table{border-collapse:collapse;font-size:13px}th,td{padding:3px 10px;text-align:left;
border-bottom:1px solid #eee}td{font-variant-numeric:tabular-nums}
.verdict{padding:12px 18px;border-radius:6px;color:#fff}.verdict .word{font-size:32px;
font-weight:bold}.verdict p{margin:4px 0 0;font-size:15px}
.pass{background:#2e8b3e}.fail{background:#b3202a}.not-evaluated{background:#6b6b6b}
.views{display:flex;flex-wrap:wrap;gap:12px}figure{margin:0}figcaption{font-size:12px;color:#555}
.swatch{display:inline-block;width:28px;height:14px;border:1px solid #888}
.none{color:#666;font-style:italic}pre{font-size:12px}
@media print{.verdict,.swatch{-webkit-print-color-adjust:exact;print-color-adjust:exact}}
</style>
)";

const char* verdictClass(Verdict verdict) {
  switch (verdict) {
    case Verdict::kPass:
      return "pass";
    case Verdict::kFail:
      return "fail";
    case Verdict::kNotEvaluated:
      break;
  }
  return "not-evaluated";
}

std::string verdictBanner(const InspectionResult& result) {
  const std::string reason =
      result.verdict_reason.empty() ? result.status.message : result.verdict_reason;
  return "<div class=\"verdict " + std::string(verdictClass(result.verdict)) +
         "\" id=\"verdict\"><div class=\"word\">" + toString(result.verdict) + "</div><p>" +
         escapeHtml(reason) + "</p></div>\n";
}

std::string provenanceSection(const ReportProvenance& p, const std::string& config_hash) {
  return "<h2>Part and traceability</h2>\n<table>\n" +
         (p.part_id.empty() ? "" : tableRow("Part id", {escapeHtml(p.part_id)})) +
         tableRow("Part (CAD file)", {escapeHtml(p.cad_file)}) +
         tableRow("Scan file", {escapeHtml(p.scan_file)}) +
         tableRow("Model id", {escapeHtml(p.model_id)}) +
         tableRow("Inspected (UTC)", {escapeHtml(p.created)}) +
         tableRow("Model key (mesh + descriptor settings)",
                  {"<code>" + escapeHtml(p.model_key) + "</code>"}) +
         tableRow("Scan file hash (XXH3-64)", {"<code>" + escapeHtml(p.scan_hash) + "</code>"}) +
         tableRow("Configuration hash (XXH3-64)", {"<code>" + config_hash + "</code>"}) +
         "</table>\n";
}

std::string transformText(const Eigen::Isometry3d& T_cad_scan) {
  std::string text;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      char cell[32];  // fixed width and sign so the columns line up
      std::snprintf(cell, sizeof(cell), c < 3 ? "%+.6f  " : "%+.7f\n", T_cad_scan(r, c));
      text += cell;
    }
  }
  return text;
}

// "±0.012° / ±0.0031 mm (1σ, noise only)": the pose's spread from its covariance.
std::string poseSpreadText(const PoseUncertainty& u) {
  if (!u.known) {
    return "unknown";
  }
  char text[96];
  std::snprintf(text, sizeof(text), "&plusmn;%.3g&deg; / &plusmn;", u.rotation_deg);
  return text + millimetres(u.translation) + " (1&sigma; from the noise alone" +
         (u.constrained ? ")" : "; some motion is not held by the scan)");
}

std::string registrationSection(const InspectionResult& r) {
  const double total = r.timings.empty() ? 0.0 : r.timings.back().seconds;
  return "<h2>Registration</h2>\n<table>\n" +
         tableRow("Status",
                  {std::string(toString(r.registration)) + " (" + toString(r.status.code) + ")"}) +
         tableRow("Message", {escapeHtml(r.status.message)}) +
         tableRow("RMSE (inliers)", {millimetres(r.rmse)}) +
         tableRow("Fitness", {percent(r.fitness)}) + tableRow("Score", {percent(r.score)}) +
         tableRow("Scan surface on the CAD", {percent(r.surface_on_cad)}) +
         tableRow("Pose fitted to the curve the CAD's faces stand for",
                  {percent(r.cad_curve_share)}) +
         tableRow("Residual noise (robust sigma)", {millimetres(r.noise_sigma)}) +
         tableRow("Inlier distance", {millimetres(r.inlier_distance)}) +
         tableRow("Pose spread (turn / centroid)", {poseSpreadText(r.pose_uncertainty)}) +
         tableRow("Scan noise", {millimetres(r.scan_noise)}) +
         tableRow("Alternative poses", {std::to_string(r.alternatives.size())}) +
         tableRow(
             "Scan points / faces",
             {std::to_string(r.counts.scan_points) + " / " + std::to_string(r.counts.scan_faces)}) +
         tableRow("Features / correspondences",
                  {std::to_string(r.counts.features) + " / " +
                   std::to_string(r.counts.correspondences)}) +
         tableRow("Run time", {number(total, 2) + " s"}) + "</table>\n" +
         "<p>T_cad_scan (scan to CAD, metres" +
         (r.datum_alignment.aligned ? ", the datum frame; the best fit is below" : "") +
         "):</p>\n<pre>" + transformText(r.T_cad_scan) + "</pre>\n" +
         (r.datum_alignment.aligned
              ? "<p>T_cad_scan of the best fit:</p>\n<pre>" +
                    transformText(r.datum_alignment.T_cad_scan_best_fit) + "</pre>\n"
              : std::string());
}

std::string statisticsSection(const DeviationStatistics& s, const ToleranceConfig& tolerance) {
  std::string html = "<h2>Deviation</h2>\n<p>Tolerance band: " + millimetres(tolerance.lower) +
                     " to " + millimetres(tolerance.upper) +
                     " (signed: positive = excess material outside the CAD surface).</p>\n";
  if (s.evaluated == 0) {
    return html + "<p class=\"none\">Not measured.</p>\n";
  }
  return html + "<table class=\"statistics\">\n" +
         tableRow("Evaluated / unmatched points",
                  {std::to_string(s.evaluated) + " / " + std::to_string(s.unmatched)}) +
         tableRow("In tolerance", {percent(s.in_tolerance_fraction)}) +
         tableRow("Coverage of the CAD surface", {percent(s.coverage)}) +
         tableRow("Mean / std / RMS",
                  {millimetres(s.mean) + " / " + millimetres(s.std) + " / " + millimetres(s.rms)}) +
         tableRow("Min / max", {millimetres(s.min) + " / " + millimetres(s.max)}) +
         tableRow("P5 / P50 / P95",
                  {millimetres(s.p5) + " / " + millimetres(s.p50) + " / " + millimetres(s.p95)}) +
         tableRow("Shape deviation mean / P95",
                  {number(s.shape_mean, 4) + " / " + number(s.shape_p95, 4)}) +
         "</table>\n" + histogramSvg(s, tolerance);
}

// The decision rule's zones (ISO 14253-1) when a measurement uncertainty was stated.
std::string conformanceSection(const ConformanceZones& z) {
  if (!(z.measurement_uncertainty > 0.0)) {
    return "";
  }
  const std::string acceptance =
      z.acceptance_lower < z.acceptance_upper
          ? millimetres(z.acceptance_lower) + " to " + millimetres(z.acceptance_upper)
          : std::string("empty (U is half the band or more)");
  return "<h2>Decision rule</h2>\n<p>ISO 14253-1 with the measurement uncertainty U = " +
         millimetres(z.measurement_uncertainty) +
         ": PASS only where conformance is proven, FAIL only where nonconformance is.</p>\n"
         "<table class=\"statistics\">\n" +
         tableRow("Acceptance zone (band narrowed by U)", {acceptance}) +
         tableRow("Rejection limits (band widened by U)",
                  {millimetres(z.rejection_lower) + " to " + millimetres(z.rejection_upper)}) +
         tableRow("Regions outside the acceptance zone / beyond the rejection limits",
                  {std::to_string(z.regions_outside_acceptance) + " / " +
                   std::to_string(z.regions_beyond_rejection)}) +
         tableRow("Points inside the acceptance zone / the rejection limits",
                  {percent(z.inside_acceptance_fraction) + " / " +
                   percent(z.inside_rejection_fraction)}) +
         "</table>\n";
}

// Pass/fail per named region (regions.h), with the band each was judged against.
std::string regionsSection(const std::vector<RegionResult>& regions) {
  if (regions.empty()) {
    return "";
  }
  std::string html =
      "<h2>Regions</h2>\n<table class=\"defects\">\n<tr><th>region</th><th>verdict</th>"
      "<th>band</th><th>points</th><th>coverage</th><th>in band</th><th>min</th><th>max</th>"
      "<th>defects</th><th>why</th></tr>\n";
  for (const RegionResult& r : regions) {
    const DeviationStatistics& d = r.deviation;
    const bool measured = d.evaluated > 0;
    html += tableRow(escapeHtml(r.name),
                     {toString(r.verdict),
                      millimetres(r.tolerance.lower) + " to " + millimetres(r.tolerance.upper),
                      std::to_string(d.evaluated),
                      percent(d.coverage),
                      measured ? percent(d.in_tolerance_fraction) : "&ndash;",
                      measured ? millimetres(d.min) : "&ndash;",
                      measured ? millimetres(d.max) : "&ndash;",
                      std::to_string(r.defects),
                      escapeHtml(r.verdict_reason)});
  }
  return html + "</table>\n";
}

// Pass/fail per comparison point (comparison_points.h): the deviation read there and its band.
std::string pointsSection(const std::vector<ComparisonPointResult>& points) {
  if (points.empty()) {
    return "";
  }
  std::string html =
      "<h2>Comparison points</h2>\n<table class=\"defects\">\n<tr><th>point</th>"
      "<th>verdict</th><th>deviation</th><th>band</th><th>points read</th><th>spread</th>"
      "<th>nominal [mm]</th><th>why</th></tr>\n";
  for (const ComparisonPointResult& p : points) {
    const bool measured = p.measured();
    const bool placed = p.normal.squaredNorm() > 0.0;
    const std::string nominal = placed ? number(p.nominal.x() * 1e3, 2) + ", " +
                                             number(p.nominal.y() * 1e3, 2) + ", " +
                                             number(p.nominal.z() * 1e3, 2)
                                       : "&ndash;";
    const std::string name =
        p.datum.empty() ? escapeHtml(p.name) : escapeHtml(p.name + " (datum " + p.datum + ")");
    html += tableRow(name,
                     {toString(p.verdict),
                      measured ? millimetres(p.deviation) : "&ndash;",
                      millimetres(p.tolerance.lower) + " to " + millimetres(p.tolerance.upper),
                      std::to_string(p.points),
                      measured ? millimetres(p.spread) : "&ndash;",
                      nominal,
                      escapeHtml(p.verdict_reason)});
  }
  return html + "</table>\n";
}

// The frame the datum targets fix: how far it lies from the best fit and what each target read
// at both.
std::string datumSection(const DatumAlignment& a) {
  if (!a.requested) {
    return "";
  }
  std::string html = "<h2>Datum alignment</h2>\n<p>" + escapeHtml(a.message) + "</p>\n";
  if (a.targets.empty()) {
    return html;
  }
  html +=
      "<table class=\"defects\">\n<tr><th>target</th><th>datum</th><th>at the best fit</th>"
      "<th>aligned</th><th>points read</th><th>nominal [mm]</th></tr>\n";
  for (const DatumTargetReading& t : a.targets) {
    const auto reading = [](double d) { return std::isfinite(d) ? millimetres(d) : "&ndash;"; };
    html += tableRow(escapeHtml(t.name),
                     {escapeHtml(t.datum),
                      reading(t.best_fit),
                      reading(t.aligned),
                      std::to_string(t.points),
                      number(t.nominal.x() * 1e3, 2) + ", " + number(t.nominal.y() * 1e3, 2) +
                          ", " + number(t.nominal.z() * 1e3, 2)});
  }
  return html + "</table>\n";
}

// `region`: the named region's name as HTML, or a dash.
std::string defectRow(std::size_t id, const DefectRegion& d, const std::string& region) {
  const std::string centroid = number(d.centroid.x() * 1e3, 2) + ", " +
                               number(d.centroid.y() * 1e3, 2) + ", " +
                               number(d.centroid.z() * 1e3, 2);
  return tableRow(std::to_string(id),
                  {d.sign > 0 ? "excess (+)" : "missing (&minus;)",
                   centroid,
                   std::to_string(d.points),
                   number(d.area * 1e6, 3),
                   millimetres(d.peak),
                   millimetres(d.mean),
                   millimetres(d.cad_chord_error),
                   region});
}

std::string defectsSection(const InspectionResult& result) {
  const std::vector<DefectRegion>& defects = result.defects;
  std::string html = "<h2>Defects</h2>\n";
  if (defects.empty()) {
    return html + "<p class=\"none\">No defect regions.</p>\n";
  }
  html +=
      "<table class=\"defects\">\n<tr><th>id</th><th>material</th><th>centroid x, y, z [mm]</th>"
      "<th>points</th><th>area [mm&sup2;]</th><th>peak</th><th>mean</th>"
      "<th title=\"how far the CAD's faces there may lie from the curved surface they stand "
      "for\">CAD chord error</th><th>region</th></tr>\n";
  for (std::size_t i = 0; i < defects.size(); ++i) {
    const std::string region = result.regionName(defects[i].region);
    html += defectRow(i, defects[i], region.empty() ? "&ndash;" : escapeHtml(region));
  }
  return html + "</table>\n";
}

std::string warningsSection(const std::vector<std::string>& warnings) {
  if (warnings.empty()) {
    return "";
  }
  std::string html = "<h2>Warnings</h2>\n<ul>\n";
  for (const std::string& warning : warnings) {
    html += "<li>" + escapeHtml(warning) + "</li>\n";
  }
  return html + "</ul>\n";
}

std::string configSection(const PipelineConfig& config, const std::string& config_hash) {
  std::string html = "<h2>Configuration</h2>\n<details><summary>Effective configuration (hash " +
                     config_hash + ")</summary>\n<table>\n";
  for (const auto& [key, value] : configEntries(config)) {
    html += tableRow(escapeHtml(key), {escapeHtml(value)});
  }
  return html + "</table>\n</details>\n";
}

std::string mapSection(const InspectionResult& result, const ToleranceBands& tolerance) {
  return "<h2>Deviation map</h2>\n" + deviationViewsHtml(result.deviation_map, tolerance) +
         colourLegendHtml(result.deviation_map, tolerance);
}

}  // namespace

std::string renderHtmlReport(const InspectionResult& result,
                             const PipelineConfig& config,
                             const ReportProvenance& provenance) {
  const std::string config_hash = configHash(config);
  const std::string part = std::filesystem::path(provenance.cad_file).filename().string();
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
         escapeHtml("Inspection " + part + ": " + toString(result.verdict)) + "</title>\n" +
         kStyle + "</head>\n<body>\n<h1>Inspection report: " + escapeHtml(part) + "</h1>\n" +
         verdictBanner(result) + provenanceSection(provenance, config_hash) +
         statisticsSection(result.deviation, config.tolerance) + regionsSection(result.regions) +
         pointsSection(result.comparison_points) + datumSection(result.datum_alignment) +
         conformanceSection(result.conformance) +
         mapSection(result,
                    toleranceBands(config.regions, result.deviation_map.region, config.tolerance)) +
         defectsSection(result) + registrationSection(result) + warningsSection(result.warnings) +
         configSection(config, config_hash) + "</body>\n</html>\n";
}

Status saveHtmlReport(const std::string& path,
                      const InspectionResult& result,
                      const PipelineConfig& config,
                      const ReportProvenance& provenance) {
  return writeOutputFile(path, renderHtmlReport(result, config, provenance), "HTML report");
}

}  // namespace freeform_inspection
