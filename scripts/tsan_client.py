#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright 2026 The freeform_inspection authors
"""The client half of scripts/tsan_node: keeps the node's service and action threads busy.

For --duration seconds, while scans stream into the node (auto_inspect), two threads run at
once: one calls ~inspect (use_last_scan) in a loop, and ~load_model every few calls (the model
is swapped under a running inspection); the other sends ~inspect_action goals and in turn
waits for the result, cancels after a random delay, or replaces the goal with a newer one
(preemption). Prints the counts and exits 0 when every call got an answer, 1 otherwise.
"""
import argparse
import random
import sys
import threading
import time

import actionlib
import rospy
from actionlib_msgs.msg import GoalStatus
from freeform_inspection.msg import InspectAction, InspectGoal, InspectionReport
from freeform_inspection.srv import Inspect, InspectRequest, LoadModel, LoadModelRequest

STATE_NAMES = {GoalStatus.SUCCEEDED: "succeeded", GoalStatus.ABORTED: "aborted",
               GoalStatus.PREEMPTED: "preempted", GoalStatus.RECALLED: "recalled",
               GoalStatus.REJECTED: "rejected", GoalStatus.LOST: "lost"}
STATUS_NAMES = {InspectionReport.PASS: "PASS", InspectionReport.FAIL: "FAIL",
                InspectionReport.NOT_EVALUATED: "NOT_EVALUATED", InspectionReport.ERROR: "ERROR"}


class Tally:
    def __init__(self):
        self.lock = threading.Lock()
        self.counts = {}
        self.errors = []

    def add(self, key):
        with self.lock:
            self.counts[key] = self.counts.get(key, 0) + 1

    def error(self, text):
        with self.lock:
            self.errors.append(text)


def service_loop(args, deadline, tally):
    inspect = rospy.ServiceProxy(args.node + "/inspect", Inspect)
    load_model = rospy.ServiceProxy(args.node + "/load_model", LoadModel)
    call = 0
    while time.time() < deadline and not rospy.is_shutdown():
        call += 1
        try:
            if args.model and call % args.load_every == 0:
                response = load_model(LoadModelRequest(path=args.model, units=args.units))
                tally.add("load_model " + ("ok" if response.success else "refused"))
                if not response.success:
                    tally.error("load_model refused: " + response.message)
                continue
            request = InspectRequest(use_last_scan=True, part_id="tsan-service-%d" % call,
                                     tolerance_upper=float("nan"), tolerance_lower=float("nan"))
            response = inspect(request)
            tally.add("inspect " + STATUS_NAMES.get(response.status, str(response.status)))
        except (rospy.ServiceException, rospy.ROSException) as error:
            if rospy.is_shutdown():
                return
            tally.error("service call %d failed: %s" % (call, error))


def action_loop(args, deadline, tally, rng):
    client = actionlib.SimpleActionClient(args.node + "/inspect_action", InspectAction)
    if not client.wait_for_server(rospy.Duration(60.0)):
        tally.error("no action server")
        return
    goal_index = 0
    while time.time() < deadline and not rospy.is_shutdown():
        goal_index += 1
        goal = InspectGoal(use_last_scan=True, part_id="tsan-action-%d" % goal_index,
                           tolerance_upper=float("nan"), tolerance_lower=float("nan"))
        client.send_goal(goal)
        mode = rng.choice(("wait", "cancel", "newer"))
        if mode == "cancel":
            # 0-2 s: cancels land while queued behind another inspection and inside stages.
            time.sleep(rng.uniform(0.0, 2.0))
            client.cancel_goal()
            tally.add("action cancel sent")
        elif mode == "newer":
            time.sleep(rng.uniform(0.0, 2.0))
            goal_index += 1
            goal.part_id = "tsan-action-%d" % goal_index
            client.send_goal(goal)  # the server preempts the previous goal for this one
            tally.add("action newer goal sent")
        if not client.wait_for_result(rospy.Duration(args.result_timeout)):
            if rospy.is_shutdown():
                return
            tally.error("goal %d (%s): no result within %.0f s" % (goal_index, mode,
                                                                 args.result_timeout))
            client.cancel_all_goals()
            continue
        tally.add("action " + STATE_NAMES.get(client.get_state(), str(client.get_state())))


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--node", default="/freeform_inspection")
    parser.add_argument("--duration", type=float, default=150.0, help="[s]")
    parser.add_argument("--model", help="~load_model path; empty: never reload")
    parser.add_argument("--units", default="mm")
    parser.add_argument("--load-every", type=int, default=6, help="every n-th service call")
    parser.add_argument("--result-timeout", type=float, default=600.0, help="[s] per goal")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("tsan_client")
    rospy.wait_for_service(args.node + "/inspect", timeout=120.0)
    tally = Tally()
    deadline = time.time() + args.duration
    threads = [threading.Thread(target=service_loop, args=(args, deadline, tally)),
               threading.Thread(target=action_loop,
                                args=(args, deadline, tally, random.Random(args.seed)))]
    start = time.time()
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    if rospy.is_shutdown():
        print("tsan_client: interrupted", file=sys.stderr)
        return 130
    print("tsan_client: %.0f s of concurrent calls" % (time.time() - start))
    for key, count in sorted(tally.counts.items()):
        print("tsan_client: %-28s %d" % (key, count))
    for error in tally.errors:
        print("tsan_client: ERROR " + error)
    return 0 if not tally.errors else 1


if __name__ == "__main__":
    sys.exit(main())
