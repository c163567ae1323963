"""A one-line progress display on stderr when it is a terminal (nothing
otherwise): done/total, percentage, rate and time left, redrawn at most four
times a second. The same line as vbsim's own (model/progress/progress_meter.h)."""
import math
import sys
import threading
import time


def clock_text(seconds):
    s = max(0, math.ceil(seconds))
    return f"{s // 3600}:{s // 60 % 60:02}:{s % 60:02}" if s >= 3600 else f"{s // 60}:{s % 60:02}"


def progress_text(label, done, total, unit, elapsed):
    rate = done / elapsed if elapsed > 0 else 0.0
    if not total:
        return f"{label}  {done} {unit}  {rate:.0f} {unit}/s"
    text = f"{label}  {100.0 * done / total:5.1f}%  {done}/{total} {unit}  {rate:.3g} {unit}/s"
    if 0 < done < total:
        text += "  ETA " + clock_text((total - done) / rate)
    return text


class ProgressLine:
    def __init__(self, label, total, unit, stream=None):
        self.stream = stream if stream is not None else (sys.stderr if sys.stderr.isatty() else None)
        self.label, self.total, self.unit = label, total, unit
        self.done, self.width = 0, 0
        self.start = self.last = time.monotonic()
        self.lock = threading.Lock()

    def update(self, done):
        with self.lock:
            self.done = done
            self._draw()

    def add(self, n):
        with self.lock:
            self.done += n
            self._draw()

    def _draw(self):
        now = time.monotonic()
        if not self.stream or now - self.last < 0.25:
            return
        self.last = now
        line = progress_text(self.label, self.done, self.total, self.unit, now - self.start)
        self.stream.write("\r" + line + " " * max(0, self.width - len(line)))
        self.stream.flush()
        self.width = len(line)

    def finish(self):
        with self.lock:
            if self.stream and self.width:
                self.stream.write("\r" + " " * self.width + "\r")
                self.stream.flush()
            self.stream = None
