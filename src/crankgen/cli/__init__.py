"""Command-line interface: `crankgen simulate | steady | sweep | reproduce | audit | continue | poincare | compile`.

main.py assembles the parser and runs a command; options.py holds the options and argument types
the commands share; runs.py the commands that run the mechanism (simulate, steady, sweep);
studies.py the studies (reproduce, audit, continue, poincare); compile.py `crankgen compile`.
"""

from .main import build_parser, main  # noqa: F401
from .options import MODELS, UsageError, _case  # noqa: F401
