"""The audit at run time: the report (report.py) of the symbolic audit (derive/audit/, loaded
lazily with SymPy), the numbers it computes from runs (numbers.py), the weight of each term group
along steady revolutions and the effect of switching groups off (term_weights.py: groups switched
off through the term masks of the declared families, Case.groups_off), and the free rod's backbone
curve (backbone.py)."""

from .report import SECTIONS, TITLES, write_report  # noqa: F401
