"""A search's progress bar for a terminal or a notebook, as `noncirc optimise` shows it.

Written by hand (about 40 lines) rather than taken from tqdm: one line redrawn with a
carriage return on stderr, which terminals and Jupyter both render, and no dependency.
"""

from __future__ import annotations

import sys
import time
from typing import Any, Optional, TextIO


def interactive() -> bool:
    """Whether a person is watching: stderr is a terminal, or this is a Jupyter kernel."""
    if "ipykernel" in sys.modules:
        return True
    stream = sys.stderr
    return stream is not None and hasattr(stream, "isatty") and stream.isatty()


class ProgressBar:
    """A `progress` callback for `optimise` that draws one line: the share of the budget,
    evaluations, designs per second, the best violation and whether a feasible design was
    found. It never stops the search; call `close()` at the end."""

    WIDTH = 24

    def __init__(self, stream: Optional[TextIO] = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.start = time.monotonic()
        self.drawn = False

    def __call__(self, info: dict[str, Any]) -> None:
        budget = max(int(info["budget"]), 1)
        done = int(info["evaluations"])
        filled = min(self.WIDTH, self.WIDTH * done // budget)
        seconds = max(time.monotonic() - self.start, 1e-9)
        cv = info["best_violation"]
        state = "feasible" if info["feasible"] else ("best CV —" if cv is None else f"best CV {cv:.3g}")
        line = f"\r[{'#' * filled}{'.' * (self.WIDTH - filled)}] {done:,}/{budget:,} designs, {done / seconds:,.0f}/s, {state}"
        self.stream.write(line)
        self.stream.flush()
        self.drawn = True

    def close(self) -> None:
        """Ends the line, if one was drawn."""
        if self.drawn:
            self.stream.write("\n")
            self.stream.flush()
