"""Progress reporting: a tqdm bar on a terminal, plain log lines otherwise."""

import sys


class Progress:
    """Callable progress(done, total) for long loops; use as a context manager."""

    def __init__(self, label, total, stream=None, enabled=True):
        self.label, self.total = label, total
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = enabled
        self._bar = None
        self._next_log = 0.1
        if enabled and hasattr(self.stream, "isatty") and self.stream.isatty():
            from tqdm import tqdm
            self._bar = tqdm(total=total, desc=label, file=self.stream, leave=False, unit="step")

    def __call__(self, done, total=None):
        if not self.enabled:
            return
        if self._bar is not None:
            self._bar.update(done - self._bar.n)
            return
        fraction = done / (total or self.total)
        if fraction >= self._next_log or done == (total or self.total):
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
