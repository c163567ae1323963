#!/usr/bin/env python3
"""Checks every numeric figure of docs/findings.md against what produces it.

    /usr/bin/python3 scripts/check_findings.py [--quick] [--vbsim build/vbsim] [--findings FILE]

Reads the page (so an edit of it is checked too), finds each figure of
scripts/findings_figures.py by its quote, rereads or reruns its source (the committed
files of docs/results/, which scripts/make_results.sh regenerates, and vbsim
commands), and prints a line per figure: `match` or `MISMATCH` with both values. A
figure matches when the source, rounded as the page writes the figure (its decimals;
an integer to units), gives the same number. Exits 1 on any mismatch, on a quote the
page no longer holds, or on a number of the page that no entry covers (a figure
without an entry). --quick skips the figures marked full (costly reruns, e.g. a
200,000-ray cycle-level bench); their quotes are still required on the page. Exit 2
on a usage error.
"""
import argparse
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from findings_figures import FIGURES, Figure, NotAFigure  # noqa: E402
from findings_sources import ROOT, SourceError  # noqa: E402

# A number not inside a name (pbrt-v4, L2, float32).
NUMBER = re.compile(r"(?<![A-Za-z0-9_.])[0-9]+(?:,[0-9]{3})*(?:\.[0-9]+)?(?:e-?[0-9]+)?(?![A-Za-z_])")


def normalise(text):
    return re.sub(r"\s+", " ", text)


def quote_pattern(quote):
    """A regex for QUOTE with one capturing group per `{}`."""
    parts = quote.split("{}")
    return "".join(re.escape(p) + ("(" + NUMBER.pattern + ")" if i < len(parts) - 1 else "")
                   for i, p in enumerate(parts))


def matches(written, value):
    """The page's WRITTEN figure agrees with VALUE rounded as it is written."""
    w = float(written.replace(",", ""))
    if "e" in written:
        return abs(value - w) <= 1e-9 * abs(w)
    decimals = len(written.split(".")[1]) if "." in written else 0
    return abs(value - w) <= 0.5 * 10 ** -decimals + 1e-9


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="skip the costly reruns (figures marked full)")
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--findings", default=os.path.join(ROOT, "docs", "findings.md"))
    args = ap.parse_args(argv)
    if not os.access(args.vbsim, os.X_OK):
        print(f"check_findings: no vbsim at {args.vbsim} (build it or pass --vbsim)", file=sys.stderr)
        return 2
    vbsim = os.path.abspath(args.vbsim)
    with open(args.findings, encoding="utf-8") as f:
        page = normalise(f.read())

    start = time.time()
    covered = set()  # start offsets of the page's numbers an entry accounts for
    failures = checked = skipped = 0
    for entry in FIGURES(vbsim):
        m = re.search(quote_pattern(entry.quote), page)
        if not m:
            print(f"MISSING  quote not on the page: \"{entry.quote}\"")
            failures += 1
            continue
        if isinstance(entry, NotAFigure):
            covered.update(n.start() + m.start() for n in NUMBER.finditer(m.group(0)))
            continue
        written = list(m.groups())
        covered.update(m.start(i + 1) for i in range(len(written)))
        if entry.full and args.quick:
            skipped += 1
            print(f"skipped  (full only) {', '.join(written)}: \"{entry.quote}\"")
            continue
        try:
            value = entry.source()
        except (SourceError, KeyError, ValueError, OSError) as e:
            print(f"ERROR    \"{entry.quote}\": {e}")
            failures += 1
            continue
        values = value if isinstance(value, tuple) else (value,)
        if len(values) != len(written):
            print(f"ERROR    \"{entry.quote}\": source gives {len(values)} values for {len(written)} figures")
            failures += 1
            continue
        for w, v in zip(written, values):
            checked += 1
            if matches(w, float(v)):
                print(f"match    page {w}, source {float(v):.6g}: \"{entry.quote}\"")
            else:
                failures += 1
                print(f"MISMATCH page {w}, source {float(v):.6g}: \"{entry.quote}\"")

    for n in NUMBER.finditer(page):
        # A number followed by '^' is the base of a power (2^20): its exponent is the figure.
        if n.start() in covered or page[n.end():n.end() + 1] == "^":
            continue
        context = page[max(0, n.start() - 50):n.end() + 30]
        print(f"NO ENTRY {n.group(0)}: \"...{context}...\" (add it to scripts/findings_figures.py)")
        failures += 1

    took = time.time() - start
    mode = "quick" if args.quick else "full"
    print(f"check_findings ({mode}): {checked} figures checked, {skipped} skipped, "
          f"{failures} problems, {took:.1f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
