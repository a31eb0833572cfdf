#!/usr/bin/env python3
"""Summarises a FontBakery 1.x `--json` report: one line per FAIL, WARN and ERROR.

Usage: fontbakery_summary.py REPORT.json LABEL

Exits 1 when any check FAILed (or FontBakery reported FATAL), 0 otherwise. WARNs and
ERRORs (checks that need the internet, or a module fontbakery could not import) are
listed, not fatal: .ci/check-fonts documents which remain and why.
"""

import json
import sys


def checks(report):
    for section in report.get("sections", []):
        yield from section.get("checks", [])


def main():
    path, label = sys.argv[1], sys.argv[2]
    with open(path, encoding="utf-8") as f:
        report = json.load(f)
    counts = {}
    failed = False
    for check in checks(report):
        status = check.get("result", "?")
        counts[status] = counts.get(status, 0) + 1
        if status not in ("FAIL", "FATAL", "WARN", "ERROR"):
            continue
        failed |= status in ("FAIL", "FATAL")
        name = check.get("module") or str(check.get("key"))
        codes = sorted(
            {
                (log.get("message") or {}).get("code", "") if isinstance(log.get("message"), dict) else ""
                for log in check.get("logs", [])
                if log.get("status") == status
            }
            - {""}
        )
        print(f"check-fonts: fontbakery: {label}: {status} {name} {' '.join(codes)}".rstrip())
    summary = ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
    print(f"check-fonts: fontbakery: {label}: {summary}")
    if not counts:
        print(f"check-fonts: fontbakery: {label}: no checks in the report")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
