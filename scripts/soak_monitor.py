#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright 2026 The freeform_inspection authors
"""The watching half of scripts/soak: counts, memory samples, the verdict.

Subscribes to the scan topic (raw, never deserialised), the node's ~result and /diagnostics;
samples the node's VmRSS from /proc every --period seconds into a CSV; once the scanner has
exited, waits for the node to finish its last scan; then prints the figures and exits 0 (PASS),
1 (FAIL) or 130 (interrupted). scripts/soak starts the processes and passes their ids.
"""
import argparse
import csv
import math
import re
import statistics
import sys
import threading
import time

import rospy
from diagnostic_msgs.msg import DiagnosticArray
from freeform_inspection.msg import InspectionReport

STATUS_NAMES = {InspectionReport.PASS: "PASS", InspectionReport.FAIL: "FAIL",
                InspectionReport.NOT_EVALUATED: "NOT_EVALUATED", InspectionReport.ERROR: "ERROR"}
# One line per published scan and per skipped one (src/ros/virtual_scanner_node.cpp).
SENT_LINE = re.compile(r"\]: scan \d+ \(seed \d+, stamp ")
SKIPPED_LINE = re.compile(r"\]: scan \d+ \(seed \d+\) not published")


def alive(pid):
    """True while the process runs; a zombie (exited, not yet reaped by the shell) is not."""
    try:
        with open("/proc/%d/stat" % pid) as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


def memory_kib(pid):
    """(VmRSS, VmHWM) in KiB, or None when the process is gone."""
    values = {}
    try:
        with open("/proc/%d/status" % pid) as status:
            for line in status:
                key, _, rest = line.partition(":")
                if key in ("VmRSS", "VmHWM"):
                    values[key] = int(rest.split()[0])
    except OSError:
        return None
    if "VmRSS" not in values:
        return None  # a zombie has no memory lines
    return values["VmRSS"], values.get("VmHWM", 0)


class Counters:
    """Everything the callbacks count; read by the sampling loop under the lock."""

    def __init__(self, node_name):
        self.lock = threading.Lock()
        self.node_name = node_name
        self.scans_seen = 0
        self.results = 0
        self.statuses = {name: 0 for name in STATUS_NAMES.values()}
        self.total_seconds = []  # the report's "total" timing, one per result
        self.diag = None  # latest counters of the node's diagnostics entry
        self.diag_wall = 0.0  # when they arrived

    def on_scan(self, _raw):
        with self.lock:
            self.scans_seen += 1

    def on_result(self, report):
        with self.lock:
            self.results += 1
            self.statuses[STATUS_NAMES.get(report.status, str(report.status))] = \
                self.statuses.get(STATUS_NAMES.get(report.status, str(report.status)), 0) + 1
            for timing in report.timings:
                if timing.stage == "total":
                    self.total_seconds.append(timing.seconds)

    def on_diagnostics(self, array):
        for status in array.status:
            # "<node name>: inspection"; the updater may or may not keep the leading slash.
            if status.name.lstrip("/") != self.node_name.lstrip("/") + ": inspection":
                continue
            values = {item.key: item.value for item in status.values}
            try:
                counters = {key: int(values[key]) for key in
                            ("scans received", "scans dropped", "inspections",
                             "inspections cancelled")}
            except (KeyError, ValueError):
                continue
            with self.lock:
                self.diag = counters
                self.diag_wall = time.time()

    def snapshot(self):
        with self.lock:
            return (self.scans_seen, self.results, dict(self.diag) if self.diag else None,
                    self.diag_wall)


def count_scanner_log(path):
    sent = skipped = 0
    with open(path, errors="replace") as log:
        for line in log:
            if SENT_LINE.search(line):
                sent += 1
            elif SKIPPED_LINE.search(line):
                skipped += 1
    return sent, skipped


def median(values):
    return statistics.median(values) if values else float("nan")


def percentile(values, share):
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(math.ceil(share * len(ordered))) - 1)]


def least_squares_slope(points):
    """Slope of y over x by least squares, NaN with fewer than 2 distinct x."""
    if len(points) < 2:
        return float("nan")
    mean_x = statistics.mean(x for x, _ in points)
    mean_y = statistics.mean(y for _, y in points)
    spread = sum((x - mean_x) ** 2 for x, _ in points)
    if spread == 0:
        return float("nan")
    return sum((x - mean_x) * (y - mean_y) for x, y in points) / spread


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--node-pid", type=int, required=True)
    parser.add_argument("--scanner-pid", type=int, required=True)
    parser.add_argument("--scanner-log", required=True)
    parser.add_argument("--node-name", default="/freeform_inspection")
    parser.add_argument("--scan-topic", default="/scan")
    parser.add_argument("--scans", type=int, required=True, help="scans the scanner was asked for")
    parser.add_argument("--warmup", type=int, required=True, help="scans before the baseline")
    parser.add_argument("--rate", type=float, required=True, help="requested rate [Hz]")
    parser.add_argument("--period", type=float, default=2.0, help="RSS sampling period [s]")
    parser.add_argument("--max-growth", type=float, default=5.0, help="[%]")
    parser.add_argument("--drain-timeout", type=float, default=120.0,
                        help="[s] for the node to finish its last scan after the scanner ends")
    parser.add_argument("--csv", required=True)
    args = parser.parse_args(rospy.myargv()[1:])

    rospy.init_node("soak_monitor")
    counters = Counters(args.node_name)
    # queue_size None: unbounded, so a busy moment loses no count. AnyMsg: no deserialisation.
    rospy.Subscriber(args.scan_topic, rospy.AnyMsg, counters.on_scan, queue_size=None)
    # The scanner's wait_for_subscribers counts subscribers of scan_truth too: be one.
    rospy.Subscriber("/scan_truth", rospy.AnyMsg, lambda _raw: None, queue_size=None)
    rospy.Subscriber(args.node_name + "/result", InspectionReport, counters.on_result,
                     queue_size=None)
    rospy.Subscriber("/diagnostics", DiagnosticArray, counters.on_diagnostics, queue_size=None)

    failures = []
    samples = []  # (elapsed, scans_seen, rss_kib)
    start = time.time()
    sending_done = None  # wall time the scanner was seen to have exited
    drained = False
    final_rss = None
    with open(args.csv, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["elapsed_s", "scans_seen", "results", "node_received", "node_dropped",
                         "node_inspections", "rss_kib", "hwm_kib", "phase"])
        next_sample = start
        while True:
            if rospy.is_shutdown():
                print("soak_monitor: interrupted", file=sys.stderr)
                return 130
            now = time.time()
            if not alive(args.node_pid):
                failures.append("the inspection node exited during the run (crash): see its log")
                break
            if sending_done is None and not alive(args.scanner_pid):
                sending_done = now
            seen, results, diag, diag_wall = counters.snapshot()
            if sending_done is not None and diag is not None and diag_wall > sending_done + 1.5:
                # Idle with nothing waiting: every received scan was inspected or dropped.
                if diag["inspections"] + diag["scans dropped"] == diag["scans received"] \
                        and diag["scans received"] >= seen and results >= diag["inspections"]:
                    drained = True
            if now >= next_sample or drained:
                memory = memory_kib(args.node_pid)
                if memory is None:
                    continue  # gone: the liveness check above reports it
                phase = "drained" if drained else ("draining" if sending_done else "sending")
                writer.writerow(["%.1f" % (now - start), seen, results,
                                 diag["scans received"] if diag else "",
                                 diag["scans dropped"] if diag else "",
                                 diag["inspections"] if diag else "", memory[0], memory[1], phase])
                out.flush()
                if phase == "sending":
                    samples.append((now - start, seen, memory[0]))
                final_rss = memory
                next_sample = now + args.period
            if drained:
                break
            if sending_done is not None and now - sending_done > args.drain_timeout:
                failures.append("the node did not finish its last scan within %.0f s of the end"
                                % args.drain_timeout)
                break
            time.sleep(0.2)
    duration = time.time() - start

    seen, results, diag, _ = counters.snapshot()
    sent, skipped = count_scanner_log(args.scanner_log)
    received = diag["scans received"] if diag else 0
    dropped = diag["scans dropped"] if diag else 0
    inspections = diag["inspections"] if diag else 0
    cancelled = diag["inspections cancelled"] if diag else 0
    with counters.lock:
        statuses = dict(counters.statuses)
        totals = list(counters.total_seconds)

    # Baseline: the samples of the W scans after the first W (warm-up); end: the samples of the
    # last W scans sent. Medians, because RSS swings within each inspection.
    warmup = max(1, args.warmup)
    base = [rss for _, s, rss in samples if warmup <= s < 2 * warmup]
    end = [rss for _, s, rss in samples if s >= sent - warmup and s >= 2 * warmup]
    first_after = next((rss for _, s, rss in samples if s >= warmup), None)
    after_warmup = [rss for _, s, rss in samples if s >= warmup]
    base_rss = median(base)
    end_rss = median(end)
    growth = 100.0 * (end_rss - base_rss) / base_rss if base and end else float("nan")

    # Trend after warm-up, least squares of RSS over scans: a leak is a steady slope, a heap
    # that grew once to hold a larger scan is a step followed by a flat line.
    trend = [(s, rss) for _, s, rss in samples if s >= warmup]
    slope = least_squares_slope(trend)
    late_slope = least_squares_slope([(s, rss) for s, rss in trend if s >= sent / 2])

    lines = []

    def say(text):
        lines.append(text)
        print("soak: " + text)

    say("scans requested %d; sent %d (scanner log, %d not published); seen on %s %d; received "
        "by the node %d" % (args.scans, sent, skipped, args.scan_topic, seen, received))
    say("results %d (~result messages; node's inspections %d), drops reported %d (diagnostics "
        "'scans dropped'), cancelled %d" % (results, inspections, dropped, cancelled))
    balanced = results + dropped == sent and inspections == results and received == sent
    say("results + drops == sent: %d + %d = %d vs %d: %s" % (
        results, dropped, results + dropped, sent, "OK" if balanced else "MISMATCH"))
    say("statuses: " + ", ".join("%s %d" % item for item in sorted(statuses.items())))
    if totals:
        say("inspection time per result ('total'): median %.2f s, mean %.2f s, p95 %.2f s, "
            "max %.2f s" % (median(totals), statistics.mean(totals), percentile(totals, 0.95),
                            max(totals)))
    send_time = (sending_done or time.time()) - start
    say("duration %.0f s (sending %.0f s, %.2f scans/s requested %.2f Hz)" % (
        duration, send_time, sent / send_time if send_time > 0 else 0.0, args.rate))
    mib = 1.0 / 1024.0
    say("RSS after warm-up (median of %d samples, scans %d-%d) %.1f MiB; at the end (median of "
        "%d samples, last %d scans) %.1f MiB; growth %.2f %% (limit %.1f %%)" % (
            len(base), warmup, 2 * warmup - 1, base_rss * mib, len(end), warmup, end_rss * mib,
            growth, args.max_growth))
    if first_after is not None and final_rss is not None:
        say("RSS first sample after warm-up %.1f MiB, final sample (idle) %.1f MiB, max after "
            "warm-up %.1f MiB, peak (VmHWM) %.1f MiB; %d samples in %s" % (
                first_after * mib, final_rss[0] * mib, max(after_warmup) * mib,
                final_rss[1] * mib, len(samples), args.csv))

    say("RSS trend after warm-up %.2f MiB per 1000 scans; over the second half of the run "
        "%.2f MiB per 1000 scans" % (slope * 1000.0 * mib, late_slope * 1000.0 * mib))

    if sent < args.scans:
        failures.append("only %d of %d scans were sent" % (sent, args.scans))
    if not balanced:
        failures.append("unaccounted scans: sent %d, received %d, results %d (node: %d), drops %d"
                        % (sent, received, results, inspections, dropped))
    if not (growth < args.max_growth):
        failures.append("RSS growth %.2f %% is not below %.1f %%" % (growth, args.max_growth))
    for failure in failures:
        say("FAIL: " + failure)
    say("PASS" if not failures else "FAIL")
    with open(args.csv.rsplit(".", 1)[0] + "_summary.txt", "w") as summary:
        summary.write("\n".join(lines) + "\n")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
