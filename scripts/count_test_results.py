#!/usr/bin/env python3
"""Counts JUnit test cases under the given directories and prints 'N passed, N failed'.

A case with a <failure> or <error> child failed; a <skipped> case is counted as skipped (the
project has none, so any skip shows up). A result file that cannot be parsed counts as a failure.
Exit status: 0 when something passed and nothing failed.
"""
import pathlib
import sys
import xml.etree.ElementTree as ElementTree


def count(directories):
    passed, failed, skipped, failures = 0, 0, 0, []
    for directory in directories:
        for path in sorted(pathlib.Path(directory).rglob("*.xml")):
            try:
                root = ElementTree.parse(path).getroot()
            except ElementTree.ParseError as error:
                failed += 1
                failures.append(f"{path}: unreadable result file ({error})")
                continue
            for case in root.iter("testcase"):
                name = f"{case.get('classname')}.{case.get('name')}"
                if case.find("failure") is not None or case.find("error") is not None:
                    failed += 1
                    failures.append(f"{path.name}: {name}")
                elif case.find("skipped") is not None:
                    skipped += 1
                else:
                    passed += 1
    return passed, failed, skipped, failures


def main():
    passed, failed, skipped, failures = count(sys.argv[1:])
    for failure in failures:
        print(f"FAILED {failure}")
    summary = f"{passed} passed, {failed} failed"
    if skipped:
        summary += f", {skipped} skipped"
    print(summary)
    return 0 if passed > 0 and failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
