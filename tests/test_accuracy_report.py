"""scripts/accuracy-report --quick end to end: the sweep on 3 tiny Newton frames, its outputs,
and that frame coherence adds zero error (same error as fc off at the same settings)."""
import csv
import math
import subprocess
import sys

import OpenImageIO as oiio

from fcutil import POVRAY_FC, TOP

ACCURACY_REPORT = TOP / "scripts" / "accuracy-report"


def test_accuracy_report_quick(tmp_path):
    assert POVRAY_FC.is_file(), "build povray-fc first (make)"
    out = tmp_path / "accuracy-report"
    done = subprocess.run([sys.executable, str(ACCURACY_REPORT), "--quick", "--out", str(out)],
                          capture_output=True, text=True, timeout=85, stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Frame coherence adds zero error" in done.stdout

    for name in ("accuracy-report.md", "accuracy-report.csv", "accuracy-report.png"):
        assert (out / name).is_file(), name
    plot = oiio.ImageInput.open(str(out / "accuracy-report.png"))
    assert plot is not None, oiio.geterror()
    assert plot.spec().width > 300 and plot.spec().height > 200
    plot.close()

    with open(out / "accuracy-report.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    by_name = {r["setting"]: r for r in rows}
    groups = {r["group"] for r in rows}
    assert groups == {"reference", "baseline", "quality", "AA threshold", "AA depth", "fc grid",
                      "fc on/off"}
    for r in rows:
        assert float(r["time_s"]) > 0
        psnr = float(r["psnr_db"])
        assert psnr > 0
        assert 0 <= float(r["differing_share"]) <= 1 and 0 <= int(r["max_error"]) <= 255
        # Invariant: an image equal to the reference has no error at all, and vice versa.
        assert math.isinf(psnr) == (int(r["max_error"]) == 0) == (float(r["differing_share"]) == 0)
    assert math.isinf(float(by_name["reference"]["psnr_db"]))

    base = by_name["baseline"]
    fc_rows = [r for r in rows if r["fc"] == "1"]
    assert len(fc_rows) == 6        # automatic grid, +YG8/16/32/64, and with antialiasing
    # Invariant: frame coherence is exact, so its error equals the fc-off error at the same
    # settings (all grids: the baseline's; with AA: the fc-off AA run's).
    for r in fc_rows:
        if "+AM2" in r["options"]:
            off = by_name["+AM2 +A0.1 +R3"]
        else:
            off = base
        for column in ("psnr_db", "max_error", "differing_share"):
            assert r[column] == off[column], (r["setting"], column)
        assert "zero added error" in r["buys_costs"]
    # Less quality is further from the reference: +Q0 (ambient only) is worse than the baseline.
    assert float(by_name["+Q0"]["psnr_db"]) < float(base["psnr_db"])
    # Antialiasing brings the render closer to the antialiased reference.
    assert float(by_name["+AM2 +A0.1 +R3"]["psnr_db"]) > float(base["psnr_db"])

    md = (out / "accuracy-report.md").read_text()
    assert "Frame coherence adds zero error" in md
    assert "max_trace_level" in md and "+Q9 +AM2 +A0.0 +R4" in md
