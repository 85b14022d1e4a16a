"""The FL_THERMAL CSV (../shared/extdata/fl_thermal/fl_thermal_data.csv) as recording-bundle
channels: what scripts/fl-thermal-bundle.py (the whole test) and scripts/fl-thermal-cycles.py
(one bundle per spindle cycle) share. Channel ids: t1..t16 degC temperatures, ch1..ch5 um
displacements, spindle_rpm with role spindle. Standard library only."""
import json
import os
import sys


def channels(source, header):
    """The bundle's column ids (time_s first) and manifest channels for the CSV header."""
    entries, ids = [], ["time_s"]
    for name in header[1:]:
        if name.endswith("_C"):
            cid, kind, unit, role = name[:-2], "temperature", "degC", ""
        elif name.endswith("_um"):
            cid, kind, unit, role = name[:-3], "displacement", "um", ""
        elif name == "spindle_rpm":
            cid, kind, unit, role = name, "other", "rpm", "spindle"
        else:
            sys.exit(f"{source}: line 1: unknown column {name!r}")
        ids.append(cid)
        entries.append({"id": cid, "kind": kind, "sensor": "unknown", "unit": unit, "role": role})
    return ids, entries


def write_manifest(bundle, session, entries):
    """bundle/manifest.json for the session block {name, started} and the channels."""
    manifest = {"format": "thermal-error-bundle", "version": 1, "session": session,
                "machine": {"name": "CNC spindle (FL_THERMAL)"}, "channels": entries}
    with open(os.path.join(bundle, "manifest.json"), "w") as f:
        json.dump(manifest, f, indent=1)
