"""Atomic output for `crankgen reproduce`: the helpers live in crankgen.io (shared by every
command); this module re-exports them under their old names."""

from ..io import (OutputExistsError, atomic_write, atomic_write_text, csv_text,  # noqa: F401
                  existing_outputs, save_figure, write_csv)
from ..io import _cell  # noqa: F401
