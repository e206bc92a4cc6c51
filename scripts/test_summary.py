#!/usr/bin/python3
"""Print 'N passed, N failed' from the test_results XML of the folders given (default _build/test_results); exit 1
on any failure or when nothing ran.

Reads gtest-*.xml (plain gtest), rosunit-*.xml (gtest nodes under rostest), MISSING-*.xml (a crashed test
binary) and rostest-*.xml (only its failures count: its passing entries wrap the rosunit cases).
"""
import glob
import os
import sys
import xml.etree.ElementTree as ET

roots = sys.argv[1:] or ["_build/test_results"]
paths = [p for root in roots for p in sorted(glob.glob(os.path.join(root, "**", "*.xml"), recursive=True))]
passed = failed = skipped = 0
for path in paths:
    name = os.path.basename(path)
    try:
        cases = list(ET.parse(path).getroot().iter("testcase"))
    except ET.ParseError:
        print(f"FAILED: unparsable result file {name}")
        failed += 1
        continue
    for tc in cases:
        if tc.find("failure") is not None or tc.find("error") is not None:
            failed += 1
            print(f"FAILED: {name}: {tc.get('classname')}.{tc.get('name')}")
        elif name.startswith("rostest-"):
            continue
        elif tc.find("skipped") is not None or tc.get("status") == "notrun" or tc.get("result") == "skipped":
            skipped += 1
        else:
            passed += 1
if skipped:
    print(f"({skipped} skipped: see the test output for the reason, e.g. ../shared/data not found)")
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed or passed == 0 else 0)
