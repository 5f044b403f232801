"""scripts/check-patches, which `make test` runs before the integration tests: it fails on a
patch without a DEP-3 header or of 150 lines or more, naming the patch."""
import subprocess

from fcutil import TOP

CHECK = TOP / "scripts" / "check-patches"

HEADER = """Description: Do one thing
 Because it was slow.
Author: povray-fc developers
Forwarded: not-needed
Last-Update: 2026-12-06
---
"""
DIFF = """--- a/source/x.cpp
+++ b/source/x.cpp
@@ -1,3 +1,4 @@
 a
+b
 c
 d
"""


def check(folder, patches, series=None):
    for name, text in patches.items():
        (folder / name).write_text(text)
    (folder / "series").write_text("\n".join(series if series is not None else patches) + "\n")
    return subprocess.run([str(CHECK), str(folder)], capture_output=True, text=True, timeout=30)


def test_the_series_passes():
    r = subprocess.run([str(CHECK)], capture_output=True, text=True, timeout=30)
    assert r.returncode == 0, r.stderr
    assert "patches, each with a DEP-3 header" in r.stdout


def test_good_patches_pass(tmp_path):
    r = check(tmp_path, {"0001-good.patch": HEADER + DIFF, "0002-also.patch": HEADER + DIFF})
    assert r.returncode == 0, r.stderr
    assert "2 patches" in r.stdout


def test_bad_headers_are_named(tmp_path):
    r = check(tmp_path, {
        "0001-no-header.patch": DIFF,
        "0002-no-why.patch": HEADER.replace(" Because it was slow.\n", "") + DIFF,
        "0003-forwarded.patch": HEADER.replace("not-needed", "yes") + DIFF,
        "0004-no-date.patch": HEADER.replace("Last-Update: 2026-12-06\n", "") + DIFF,
        "0005-no-author.patch": HEADER.replace("Author: povray-fc developers\n", "") + DIFF,
    })
    assert r.returncode == 1
    lines = r.stderr.splitlines()
    assert any(l.startswith("check-patches: 0001-no-header.patch: no DEP-3 header") for l in lines)
    assert any(l.startswith("check-patches: 0002-no-why.patch: ") and "saying why" in l for l in lines)
    assert any(l.startswith("check-patches: 0003-forwarded.patch: ") and "not-needed" in l
               for l in lines)
    assert any(l.startswith("check-patches: 0004-no-date.patch: ") and "Last-Update" in l
               for l in lines)
    assert any(l.startswith("check-patches: 0005-no-author.patch: ") and "Author" in l for l in lines)


def test_long_patches_are_named(tmp_path):
    body = "".join(" line %d\n" % i for i in range(150 - HEADER.count("\n") - DIFF.count("\n")))
    exactly_150 = HEADER + DIFF + body
    assert exactly_150.count("\n") == 150
    r = check(tmp_path, {"0001-long.patch": exactly_150,
                         "0002-short.patch": HEADER + DIFF + body[body.index("\n") + 1:]})
    assert r.returncode == 1
    assert r.stderr.splitlines() == [
        "check-patches: 0001-long.patch: 150 lines, at most 149: more than one concern, or "
        "logic that belongs in the project's folders"]


def test_series_and_files_agree(tmp_path):
    r = check(tmp_path, {"0001-listed.patch": HEADER + DIFF, "0002-stray.patch": HEADER + DIFF},
              series=["0001-listed.patch", "0003-missing.patch"])
    assert r.returncode == 1
    assert "check-patches: 0002-stray.patch: not in the series" in r.stderr
    assert "check-patches: 0003-missing.patch: listed in the series, but there is no such file" \
        in r.stderr
