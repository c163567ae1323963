#!/usr/bin/env python3
"""scripts/check_findings.py end to end (needs the vbsim binary):
the committed docs/findings.md passes the quick check; a copy with one figure changed,
one with a quoted sentence reworded and one with a number no entry covers each fail
(exit 1) and name the problem."""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "check_findings.py")


def run(vbsim, findings=None):
    cmd = [sys.executable, SCRIPT, "--quick", "--vbsim", vbsim]
    if findings:
        cmd += ["--findings", findings]
    return subprocess.run(cmd, capture_output=True, text=True)


def expect_failure(vbsim, page, old, new, needle):
    assert old in page, f"test fixture: '{old}' is not on the page"
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "findings.md")
        with open(path, "w") as f:
            f.write(page.replace(old, new, 1))
        r = run(vbsim, path)
    assert r.returncode == 1, f"'{old}' -> '{new}': exit {r.returncode}\n{r.stdout}{r.stderr}"
    assert needle in r.stdout, f"'{old}' -> '{new}': no '{needle}' in\n{r.stdout}"


def main():
    vbsim = sys.argv[1]
    r = run(vbsim)
    assert r.returncode == 0, f"docs/findings.md does not pass the quick check:\n{r.stdout}{r.stderr}"
    assert "MISMATCH" not in r.stdout and " 0 problems" in r.stdout, r.stdout
    with open(os.path.join(ROOT, "docs", "findings.md")) as f:
        page = f.read()
    # A figure edited on the page (tmin on paths is 297 per million in accuracy.md).
    expect_failure(vbsim, page, "family (297 per million)", "family (298 per million)",
                   "MISMATCH page 298, source 297")
    # A quoted sentence reworded: its entry no longer finds it.
    expect_failure(vbsim, page, "wall of box corners (705140)",
                   "wall of boxed corners (705140)", "MISSING")
    # A new number without an entry.
    expect_failure(vbsim, page, "## Errors no method avoids",
                   "## Errors no method avoids\nAbout 12345 rays per million.", "NO ENTRY 12345")
    print("check_findings_run: ok")


if __name__ == "__main__":
    main()
