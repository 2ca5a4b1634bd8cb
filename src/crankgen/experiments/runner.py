"""`crankgen reproduce`: recompute Figures 2-8 and findings.md into an output folder."""

import inspect
import math
import sys
import time
from pathlib import Path

from .. import steady as _steady
from ..errors import CrankgenError
from ..cases import Case
from ..progress import Progress
from ..simulation import simulate_many
from . import figures as F
from . import plots, report
from .config import FIGURES, ReproduceConfig
from .io import OutputExistsError, existing_outputs, save_figure, write_csv, atomic_write_text


def output_names(figures=FIGURES):
    names = []
    for f in figures:
        names += [f"fig{f}.png", f"fig{f}.csv"]
    return names + ["convergence.png", "convergence.csv", "findings.md"]


class Context:
    """What the figure functions need: the config, logging, and the two engines with progress."""

    def __init__(self, config, quiet=False, stream=None):
        self.config = config
        self.quiet = quiet
        self.stream = stream if stream is not None else sys.stderr
        self.steady_calls = 0
        self.steady_cases = 0

    def log(self, message):
        if not self.quiet:
            print(f"reproduce: {message}", file=self.stream, flush=True)

    def _steady_options(self):
        """config.steady_options restricted to what steady_states accepts."""
        params = inspect.signature(_steady.steady_states).parameters
        return {k: v for k, v in self.config.steady_options.items() if k in params}

    def steady(self, cases, label):
        """All cases in one batched steady_states call, with a progress bar."""
        cases = list(cases)
        self.log(f"{label}: {len(cases)} steady states")
        self.steady_calls += 1
        self.steady_cases += len(cases)
        with Progress(label, len(cases), stream=self.stream, enabled=not self.quiet) as bar:
            states = _steady.steady_states(cases, progress=bar, **self._steady_options())
        if len(states) != len(cases):
            raise CrankgenError(f"steady_states returned {len(states)} results for {len(cases)} cases")
        return states

    def transients(self, specs, label):
        """Runs from zero initial conditions, batched in the compiled engine (simulate_many); a run
        that fails is returned with status "failed" and where it failed."""
        specs = list(specs)
        cfg = self.config
        groups = {}
        for i, s in enumerate(specs):
            groups.setdefault(s.revolutions, []).append(i)
        total = sum(max(1, int(round(s.revolutions * s.steps_per_rev))) for s in specs)
        self.log(f"{label}: {len(specs)} runs, {total} time steps")
        out = [None] * len(specs)
        with Progress(label, total, stream=self.stream, enabled=not self.quiet) as bar:
            offset = 0
            for revs, idx in groups.items():
                cases = []
                for i in idx:
                    s, m = specs[i], F.model_spec(specs[i].model)
                    cases.append(Case(a=cfg.a, eps=s.eps, ms=s.ms, mu=cfg.mu, omega=s.omega,
                                      approach=s.approach, formulation=m.formulation,
                                      damping=m.damping, membrane=m.membrane,
                                      n_elements=s.n_elements, steps_per_rev=s.steps_per_rev))
                results = simulate_many(cases, revs, progress=lambda d, _t, o=offset: bar(o + d))
                for i, r in zip(idx, results):
                    if isinstance(r, CrankgenError):
                        out[i] = F.TransientCurve(specs[i], status="failed", message=str(r),
                                                  fail_time=math.nan if r.time is None else float(r.time))
                    else:
                        out[i] = F.TransientCurve(specs[i], t=r.t, v_mid=r.v_mid)
                offset += sum(max(1, int(round(revs * specs[i].steps_per_rev))) for i in idx)
        return out


def reproduce(out="results", config=None, force=False, quiet=False, figures=FIGURES, stream=None):
    """Compute the selected figures (always with the convergence check), write one PNG and one CSV
    per figure, convergence.{png,csv} and findings.md into `out`.  Without force, refuses (before
    computing anything) if any of those files already exists; other files are left alone."""
    config = config or ReproduceConfig.full()
    figures = tuple(sorted(set(int(f) for f in figures)))
    bad = [f for f in figures if f not in FIGURES]
    if bad:
        raise CrankgenError(f"figures must be among {', '.join(map(str, FIGURES))}; got {bad}")
    out = Path(out)
    names = output_names(figures)
    if out.exists() and not out.is_dir():
        raise OutputExistsError(f"{out} exists and is not a folder")
    clash = existing_outputs(out, names) if out.exists() else []
    if clash and not force:
        more = f" and {len(clash) - 1} more" if len(clash) > 1 else ""
        raise OutputExistsError(f"{out} already holds {clash[0]}{more}; use --force to overwrite")
    out.mkdir(parents=True, exist_ok=True)
    ctx = Context(config, quiet=quiet, stream=stream)
    started = time.perf_counter()
    timings = {}
    written = []

    def write(name, kind, payload):
        # refuse again at write time (a file may have appeared since the start)
        overwrite = force
        if kind == "csv":
            write_csv(out / name, *payload, overwrite=overwrite)
        elif kind == "png":
            save_figure(payload, out / name, overwrite=overwrite, dpi=config.dpi)
        else:
            atomic_write_text(out / name, payload, overwrite=overwrite)
        written.append(name)

    t0 = time.perf_counter()
    conv = F.convergence_study(ctx)
    counts = conv["counts"]
    timings["convergence"] = time.perf_counter() - t0
    ctx.log("element counts used: " + ", ".join(f"{m} {a}: {n}" for (m, a), n in counts.items()))

    data = {}
    funcs = {2: F.figure2, 3: F.figure3, 4: F.figure4, 5: F.figure5, 6: F.figure6,
             7: F.figure7, 8: F.figure8}
    refine = None
    for f in figures:
        t0 = time.perf_counter()
        data[f] = funcs[f](ctx, counts)
        write(f"fig{f}.csv", "csv", F.csv_table(data[f]))
        write(f"fig{f}.png", "png", plots.plot_figure(data[f], config, counts))
        timings[f"figure {f}"] = time.perf_counter() - t0
    if config.refine_omegas or config.refine_fig5:
        t0 = time.perf_counter()
        refine = F.refinement_check(ctx, counts, data.get(6), data.get(5))
        timings["refinement check"] = time.perf_counter() - t0
    write("convergence.csv", "csv", F.convergence_table(conv, refine))
    write("convergence.png", "png", plots.plot_convergence(conv, config))
    total = time.perf_counter() - started
    text = report.findings_markdown(config, conv, refine, data, timings, total,
                                    files=[n for n in names if n != "findings.md"])
    write("findings.md", "text", text)
    ctx.log(f"wrote {len(written)} files to {out} in {total:.1f} s")
    return dict(out=out, files=written, wall_time=total, data=data, convergence=conv,
                refinement=refine, timings=timings)
