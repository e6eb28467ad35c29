"""SAP2000 / ETABS / CSiBridge "Export to Excel" workbooks, written from the programs'
documented layout with openpyxl: one sheet per table, named by the table; row 1 the title
`TABLE:  "Joint Displacements"`, row 2 the field names, row 3 the units, then the long
table (one row per object per output step), numbers as number cells.

    python3 make_sap2000_xlsx.py TRACE.csv OUT.xlsx     # the fixture of the fe run
    python3 make_sap2000_xlsx.py --malformed DIR        # the small files of the unit tests

TRACE.csv is a trace rockslide writes (`time [s],rel_disp [m],…,resistance [N],…`); the
fixture `sap2000-pepo.xlsx` beside this script was written from the fe engine's single
PEPO trace of `tests/all/external_programs.rs` (`rockslide run` on that case
writes it as `fe-single.csv`): joints 1 (the ground, at rest) and 2 (the mass, `U1` its relative
displacement, m), link 1 (`P` the weight as a tension-positive −1000 kN, `V2` the
resistance, kN).
"""

import csv
import datetime
import os
import sys

from openpyxl import Workbook

JOINT_FIELDS = ["Joint", "OutputCase", "CaseType", "StepType", "StepNum", "U1", "U2", "U3"]
JOINT_UNITS = ["Text", "Text", "Text", "Text", "Sec", "m", "m", "m"]
LINK_FIELDS = ["Link", "LinkElem", "OutputCase", "CaseType", "StepType", "StepNum", "P", "V2"]
LINK_UNITS = ["Text", "Text", "Text", "Text", "Text", "Sec", "KN", "KN"]


def workbook():
    wb = Workbook()
    wb.remove(wb.active)
    # a fixed date, so that the same input writes the same workbook
    when = datetime.datetime(2026, 11, 29)
    wb.properties.created = when
    wb.properties.modified = when
    wb.properties.creator = "rockslide fixture"
    return wb


def table(wb, title, fields, units, rows):
    """One sheet: the title row, the field names, the units row (if given), the rows."""
    ws = wb.create_sheet(title[:31])
    ws.append([f'TABLE:  "{title}"'])
    ws.append(fields)
    if units is not None:
        ws.append(units)
    for row in rows:
        ws.append(row)
    return ws


def joint_rows(times, u1):
    for t, u in zip(times, u1):
        yield [1, "TH", "NonDirHist", "Time", t, 0.0, 0.0, 0.0]
        yield [2, "TH", "NonDirHist", "Time", t, u, 0.0, 0.0]


def link_rows(times, v2):
    for t, v in zip(times, v2):
        yield [1, 1, "TH", "NonDirHist", "Time", t, -1000.0, v]


def save(wb, path):
    wb.save(path)
    print(f"wrote {path}")


def fixture(trace_csv, out):
    with open(trace_csv, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    col = {name: i for i, name in enumerate(header)}
    data = [[float(x) for x in r] for r in rows[1:] if r]
    times = [r[col["time [s]"]] for r in data]
    u1 = [r[col["rel_disp [m]"]] for r in data]
    v2 = [r[col["resistance [N]"]] / 1000.0 for r in data]
    wb = workbook()
    table(wb, "Joint Displacements", JOINT_FIELDS, JOINT_UNITS, joint_rows(times, u1))
    table(wb, "Element Forces - Links", LINK_FIELDS, LINK_UNITS, link_rows(times, v2))
    save(wb, out)


def malformed(folder):
    """A small valid workbook and one file per malformed variant the unit tests refuse."""
    times = [0.0, 0.005, 0.01]
    u1 = [0.0, 0.0003267, 0.0012]
    v2 = [0.0, 1.652, 3.1]
    os.makedirs(folder, exist_ok=True)

    wb = workbook()
    table(wb, "Joint Displacements", JOINT_FIELDS, JOINT_UNITS, joint_rows(times, u1))
    table(wb, "Element Forces - Links", LINK_FIELDS, LINK_UNITS, link_rows(times, v2))
    save(wb, os.path.join(folder, "small.xlsx"))

    wb = workbook()
    table(wb, "Joint Displacements", JOINT_FIELDS, None, joint_rows(times, u1))
    table(wb, "Element Forces - Links", LINK_FIELDS, LINK_UNITS, link_rows(times, v2))
    save(wb, os.path.join(folder, "no-units-row.xlsx"))

    wb = workbook()
    table(wb, "Joint Displacements", JOINT_FIELDS, JOINT_UNITS, joint_rows(times, u1))
    ws = table(wb, "Element Forces - Links", LINK_FIELDS, LINK_UNITS, link_rows(times, v2))
    ws["H5"] = "1.652 kN"  # text where the export writes a number
    save(wb, os.path.join(folder, "text-in-number.xlsx"))

    wb = workbook()
    table(wb, "Joint Displacements", JOINT_FIELDS, JOINT_UNITS, joint_rows(times, u1))
    save(wb, os.path.join(folder, "no-link-sheet.xlsx"))


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--malformed":
        malformed(sys.argv[2])
    elif len(sys.argv) == 3:
        fixture(sys.argv[1], sys.argv[2])
    else:
        sys.exit(__doc__)
