"""JUnit XML for CI servers: one test case per check row, a failure carrying the row's report."""

from __future__ import annotations

import xml.etree.ElementTree as ET

__internal__ = True  # the command's JUnit writer: used through `wavephys check --junit`, not fuzzed as public API

__all__ = ["junit_xml"]


def junit_xml(suite: str, rows: dict, seconds: dict | None = None, skipped: dict | None = None) -> str:
    """The rows of a check as a JUnit XML document (a ``<testsuite>`` of ``<testcase>`` elements).

    Parameters
    ----------
    suite : str
        The suite's name (the record's source, say).
    rows : dict of str to Check
        The rows by check name; a row that is not ok becomes a ``<failure>`` with its report.
    seconds : dict of str to float, optional
        Run time per check, s.
    skipped : dict of str to str, optional
        Checks not run, with why: ``<skipped>`` cases.

    Returns
    -------
    str
        The XML document, UTF-8 declared.
    """
    seconds, skipped = seconds or {}, skipped or {}
    failures = sum(not r.ok for r in rows.values())
    root = ET.Element("testsuite", name=str(suite), tests=str(len(rows) + len(skipped)), failures=str(failures),
                      skipped=str(len(skipped)), time=f"{sum(seconds.values()):.3f}")
    for name, row in rows.items():
        case = ET.SubElement(root, "testcase", classname="wavephys.check", name=name,
                             time=f"{seconds.get(name, 0.0):.3f}")
        if not row.ok:
            ET.SubElement(case, "failure", message=row.report()[:500]).text = row.report()
        else:
            ET.SubElement(case, "system-out").text = row.report()
    for name, why in skipped.items():
        case = ET.SubElement(root, "testcase", classname="wavephys.check", name=name, time="0")
        ET.SubElement(case, "skipped", message=why)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
