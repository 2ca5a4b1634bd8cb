"""Progress reporting: a tqdm bar on a terminal, plain log lines otherwise.

Progress and log output is best effort: it never stops a computation.  `BestEffortStream` wraps a
text stream (stderr, stdout) so that the first OSError of a write or flush (a full disk or a
closed pipe behind the stream) is swallowed and the stream goes silent for the rest of the run;
the command line wraps sys.stdout and sys.stderr in it, and Progress wraps whatever it is given.
"""

import sys
import time


class BestEffortStream:
    """A text stream whose writes never raise OSError: after the first failure (recorded in
    `failure`) every later write is dropped.  Each write is flushed at once, so nothing is left
    in the wrapped stream's buffer to fail again when the interpreter exits."""

    def __init__(self, stream):
        self.stream = stream
        self.failure = None

    @classmethod
    def wrap(cls, stream):
        return stream if isinstance(stream, cls) else cls(stream)

    def write(self, text):
        if self.failure is None:
            try:
                self.stream.write(text)
                self.stream.flush()
            except OSError as exc:
                self._fail(exc)
        return len(text)

    def flush(self):
        if self.failure is None:
            try:
                self.stream.flush()
            except OSError as exc:
                self._fail(exc)

    def _fail(self, exc):
        self.failure = exc
        try:                          # drop what the failed write left in the buffer, if anything
            self.stream.flush()
        except (OSError, ValueError):
            pass

    def isatty(self):
        try:
            return self.failure is None and self.stream.isatty()
        except (OSError, ValueError, AttributeError):
            return False

    def __getattr__(self, name):      # encoding, fileno, ... of the wrapped stream
        return getattr(self.stream, name)


class Progress:
    """Callable progress(done, total) for long loops; use as a context manager.  Off a terminal
    it prints a line at every tenth of the total, and, with `interval` (seconds), also when that
    long has passed since the last line and something was done."""

    def __init__(self, label, total, stream=None, enabled=True, interval=None):
        self.label, self.total = label, total
        self.interval = interval
        self._last_time, self._last_done = time.monotonic(), 0
        self.stream = BestEffortStream.wrap(stream if stream is not None else sys.stderr)
        self.enabled = enabled
        self._bar = None
        self._next_log = 0.1
        if enabled and self.stream.isatty():
            from tqdm import tqdm
            self._bar = tqdm(total=total, desc=label, file=self.stream, leave=False, unit="step")

    def __call__(self, done, total=None):
        if not self.enabled:
            return
        if self._bar is not None:
            self._bar.update(done - self._bar.n)
            return
        fraction = done / (total or self.total)
        now = time.monotonic()
        due = (self.interval is not None and done > self._last_done
               and now - self._last_time >= self.interval)
        if fraction >= self._next_log or done == (total or self.total) or due:
            self._last_time, self._last_done = now, done
            print(f"{self.label}: {done}/{total or self.total} ({100 * fraction:.0f} %)",
                  file=self.stream, flush=True)
            while self._next_log <= fraction:
                self._next_log += 0.1

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self._bar is not None:
            self._bar.close()
        return False
