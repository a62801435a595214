"""Progress of long calls: a bar on stderr when it is a terminal, nothing otherwise.

Every long call takes ``progress``: None (the default) shows the bar only on a terminal, True
always, False never, and a callable ``progress(done, total)`` (total 0 when unknown) is called
instead. The C++ side calls back at most ten times a second, so the bar costs nothing per scan.
"""

import shutil
import sys
import time


class Bar:
    """A one-line bar redrawn in place: ``label |#####     | 40/100 unit [00:04<00:06, 9.8 unit/s]``;
    without a total, the count, the elapsed time and the rate."""

    def __init__(self, label, unit, stream=None):
        self._label = label
        self._unit = unit
        self._stream = stream if stream is not None else sys.stderr
        self._start = time.monotonic()
        self._done = 0
        self._total = 0
        self._drawn = False
        self._width = 0

    def __call__(self, done, total):
        self._done, self._total = done, total
        self._draw(final=False)

    def close(self):
        if self._drawn:
            self._draw(final=True)

    def _draw(self, final):
        elapsed = time.monotonic() - self._start
        rate = self._done / elapsed if elapsed > 0 else 0.0
        stats = f"{self._done}/{self._total} {self._unit}" if self._total else f"{self._done} {self._unit}"
        timing = _clock(elapsed)
        if self._total and rate > 0 and not final:
            timing += "<" + _clock(max(self._total - self._done, 0) / rate)
        line = f"{stats} [{timing}, {rate:.1f} {self._unit}/s]"
        if self._total:
            width = max(10, shutil.get_terminal_size((80, 20)).columns - len(self._label) - len(line) - 5)
            filled = int(width * min(self._done / self._total, 1.0))
            line = f"|{'#' * filled}{' ' * (width - filled)}| " + line
        line = f"{self._label} {line}"
        padding = " " * max(self._width - len(line), 0)  # wipe the end of a longer line
        self._width = len(line)
        self._stream.write("\r" + line + padding + ("\n" if final else ""))
        self._stream.flush()
        self._drawn = True


def _clock(seconds):
    minutes, seconds = divmod(int(seconds), 60)
    return f"{minutes:02d}:{seconds:02d}"


class _Silent:
    def __call__(self, done, total):
        pass

    def close(self):
        pass


def make_progress(progress, label, unit):
    """What a long call reports to: the bar, the caller's callable, or nothing. Returns an object
    called as ``(done, total)`` with a ``close()`` for the end (a callable given by the caller is
    wrapped so that close() does nothing)."""
    if callable(progress) and not isinstance(progress, bool):
        return _Forward(progress)
    if progress is None:
        progress = _is_terminal(sys.stderr)
    return Bar(label, unit) if progress else _Silent()


class _Forward:
    def __init__(self, callback):
        self._callback = callback

    def __call__(self, done, total):
        self._callback(done, total)

    def close(self):
        pass


def _is_terminal(stream):
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False
