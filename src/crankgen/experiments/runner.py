"""`crankgen reproduce`: recompute Figures 2-8 and findings.md into an output folder, resumably
(manifest.py records what made each file; a rerun computes only what is missing or stale)."""

import fcntl
import inspect
import math
import os
import sys
import threading
import time
from pathlib import Path

import numpy as np

from ..analyses import steady as _steady
from ..analyses import theory
from ..errors import CrankgenError
from ..declaration.cases import Case
from ..progress import Progress
from ..analyses.simulation import simulate_many
from . import bifurcations as BF
from . import exact_rod as XR
from . import figures as F
from . import plots, report
from .config import FIGURES, ReproduceConfig
from .threads import stopping
from ..results.provenance import code_version
from .io import (OutputExistsError, atomic_write_text, read_json, remove_temporaries, save_figure,
                 write_csv, write_json)
from .manifest import NAME as MANIFEST, Manifest


DATA = "data"          # subfolder of the computed data that findings.md is built from (JSON)


BIFURCATION_FILES = ["bifurcations.csv", "bifurcation_branches.csv", "bifurcation_beyond.csv"]
EXACT_FILES = ["exact_rod.png", "exact_rod_points.csv", "exact_rod_branches.csv", "exact_rod_character.csv"]


def output_names(figures=FIGURES):
    """The figure, bifurcation (with Figure 6), convergence and findings files of a run over
    `figures`."""
    names = []
    for f in figures:
        names += [f"fig{f}.png", f"fig{f}.csv"]
    if 6 in figures:
        names += BIFURCATION_FILES + EXACT_FILES
    return names + ["convergence.png", "convergence.csv", "findings.md"]


def step_files(step):
    """Files a step writes (relative to the output folder)."""
    if step.startswith("figure "):
        f = step.split()[1]
        return [f"{DATA}/fig{f}.json", f"fig{f}.csv", f"fig{f}.png"]
    return {"convergence check": [f"{DATA}/convergence.json"],
            "bifurcations": [f"{DATA}/bifurcations.json", *BIFURCATION_FILES],
            "exact rod": [f"{DATA}/exact_rod.json", *EXACT_FILES],
            "refinement check": [f"{DATA}/refinement.json"],
            "convergence files": ["convergence.csv", "convergence.png"],
            "findings": ["findings.md"]}[step]


STEPS = ("convergence check", "bifurcations", "exact rod", *[f"figure {f}" for f in FIGURES],
         "refinement check", "convergence files", "findings")


def all_files():
    out = [MANIFEST]
    for step in STEPS:
        out += step_files(step)
    return out


_COMMON = ("a", "eps", "ms", "mu", "steps_per_rev", "steady_options")
_FIGURE_KEYS = {2: ("fig2_omega", "fig2_elements", "fig2_revolutions"),
                3: ("fig3_omega", "fig3_elements", "fig3_steps", "fig3_revolutions"),
                4: ("fig4_omega", "fig4_revolutions", "fig4_ms"),
                5: ("fig5_omegas", "fig5_eps", "envelope_revolutions", "envelope_window", "exact_rows",
                    "exact_row_elements"),
                6: ("fig6_omegas", "fig6_eps", "fig6_inset_ylim", "envelope_revolutions",
                    "envelope_window", "exact_rows", "exact_row_elements"),
                7: ("fig7_omega", "ext_ms", "crossing_rel_tol"),
                8: ("fig8_omega", "ext_ms", "crossing_rel_tol")}
_BIFURCATION_KEYS = ("fig6_eps", "bif_range", "bif_elements", "bif_steps_per_rev", "bif_max_period",
                     "bif_dp_max", "bif_tol", "bif_beyond_values", "bif_transient", "bif_samples")
_EXACT_KEYS = ("exact_mechanisms", "exact_eps", "exact_range", "exact_elements", "exact_steps",
               "exact_max_period", "exact_dp_max", "exact_rocker", "exact_tol", "exact_match", "exact_snap_omega",
               "exact_snap_revolutions", "exact_character_omegas", "exact_character_transient",
               "exact_character_samples", "exact_character_steps", "dpi")


def _settings(cfg, keys, **extra):
    d = cfg.as_dict()
    out = {k: d[k] for k in _COMMON + tuple(keys)}
    out["models"] = [m.__dict__ for m in F.MODELS]
    out.update(extra)
    return out


def _counts_list(counts):
    return sorted([m, ap, n] for (m, ap), n in counts.items())



# how long the first run on a machine compiles what reproduce uses (the README says the same):
# measured 27 s on two idle cores (bench/results.json) and 60 s with the cores shared
COMPILE_TIME = "about 30 s on two idle cores, a minute or more when they are busy"

class Context:
    """What the figure functions need: the config, logging, and the two engines with progress."""

    def __init__(self, config, quiet=False, stream=None):
        self.config = config
        self.quiet = quiet
        self.stream = stream if stream is not None else sys.stderr
        self.steady_calls = 0
        self.steady_cases = 0
        self.engine = None          # (seconds, compiled) of the engine's start-up in this run
        self.stop = threading.Event()   # set when a step run in pieces is interrupted (threads.py)
        self._continuations = {}        # Context.continuation's diagrams of this run
        self._writing = threading.Lock()

    def start_engine(self):
        """Load the compiled engine (compile it, on a machine's first run) before the first step
        that needs it, and time that on its own: every path reproduce uses (steady states of one
        and of several cases, transients with states, the revolution map of the continuation)."""
        if self.engine is not None:
            return
        from ..analyses.bifurcation.mechanism import MechanismMap
        from ..engine.cache import is_warm
        compiled = not is_warm()
        t0 = time.perf_counter()
        self.log("starting the compiled engine" + (f" (compiling it for this machine, once: {COMPILE_TIME})"
                                                   if compiled else ""))
        cases = [Case(n_elements=1, steps_per_rev=20, omega=w) for w in (0.8, 0.9)]
        _steady.steady_states(cases[:1], max_revolutions=2)
        _steady.steady_states(cases, max_revolutions=2)
        simulate_many(cases, 0.2, keep_states=True)
        fmap = MechanismMap(cases[0], "omega")
        fmap.evaluate(np.zeros(fmap.dim), 0.8)
        self.engine = (time.perf_counter() - t0, compiled)

    def continuation(self, mech, parameter, start, stop, progress=None, **settings):
        """crankgen.continuation(mech, parameter, start, stop, progress=progress, **settings), computed
        once per run: a step that asks for the very continuation an earlier step computed (the same
        case, range and settings: the quick preset's consistent slider-crank in the bifurcations and
        exact-rod steps) gets that one's diagram."""
        from ..analyses.bifurcation import continuation

        fields = {k: settings[k] for k in ("model", "approach", "n_elements", "steps_per_rev") if k in settings}
        try:                            # the case as built (a model's defaults written out or not)
            key = (Case.from_mechanism(mech, **fields, **{parameter: start}), parameter, float(start), float(stop),
                   tuple(sorted((k, v) for k, v in settings.items() if k not in fields)))
            hash(key)
        except (TypeError, CrankgenError):
            key = None
        if key is not None and key in self._continuations:
            if progress is not None:
                progress("the same continuation as an earlier step's: its diagram is reused")
            return self._continuations[key]
        d = continuation(mech, parameter, start, stop, progress=progress, **settings)
        if key is not None:
            self._continuations[key] = d
        return d

    def log(self, message):
        stopping(self.stop)         # a piece of an interrupted step ends here (threads.py)
        if not self.quiet:
            with self._writing:     # one whole line at a time: pieces of a step log from two threads
                self.stream.write(f"reproduce: {message}\n")
                self.stream.flush()

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
        """Runs from zero initial conditions, batched in the compiled engine (simulate_many), with
        the axial strain of every step; a run that fails is returned with where it failed and status
        DIVERGED (an ill-posed approach) or "failed"."""
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
                    s = specs[i]
                    cases.append(Case(a=cfg.a, eps=s.eps, ms=s.ms, mu=cfg.mu, omega=s.omega,
                                      approach=s.approach, model=F.model_spec(s.model).key,
                                      n_elements=s.n_elements, steps_per_rev=s.steps_per_rev))
                results = simulate_many(cases, revs, progress=lambda d, _t, o=offset: bar(o + d),
                                        keep_states=True)
                for i, r in zip(idx, results):
                    if isinstance(r, CrankgenError):
                        part = getattr(r, "partial", None)
                        out[i] = F.TransientCurve(specs[i], status=F.failure_status(specs[i].approach),
                                                  message=str(r),
                                                  fail_time=math.nan if r.time is None else float(r.time),
                                                  t=None if part is None else np.asarray(part.t),
                                                  v_mid=None if part is None else np.asarray(part.v_mid),
                                                  axial_strain=None if part is None else
                                                  theory.axial_strain(part, per_step=True))
                    else:
                        out[i] = F.TransientCurve(specs[i], t=r.t, v_mid=r.v_mid,
                                                  axial_strain=theory.axial_strain(r, per_step=True))
                offset += sum(max(1, int(round(revs * specs[i].steps_per_rev))) for i in idx)
        return out


def run_version():
    """What made a step: crankgen.results.provenance.code_version() and a hash of this package's source
    (figures, plots, claims, findings), so that a rerun with changed reproduce code recomputes."""
    import hashlib
    h = hashlib.sha256()
    for p in sorted(Path(__file__).parent.glob("*.py")):
        h.update(p.name.encode())
        h.update(p.read_bytes())
    return dict(code_version(), experiments=h.hexdigest()[:16])


class _Lock:
    """An exclusive lock on the output folder (flock), so that two runs never write it at once."""

    def __init__(self, folder):
        self.fd = os.open(folder, os.O_RDONLY)
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(self.fd)
            raise CrankgenError(f"another crankgen reproduce is writing to {folder}") from None
        except OSError:         # a file system without flock: run unlocked
            pass

    def release(self):
        os.close(self.fd)


def reproduce(out="results", config=None, force=False, quiet=False, figures=FIGURES, stream=None):
    """Compute the selected figures (always with the convergence check) into `out`: one PNG, one
    CSV and one data file (data/figN.json) per figure, convergence.{png,csv} and findings.md, with
    manifest.json recording what made each.  With Figure 6 the bifurcations step runs first
    (bifurcations.py: the continuation of approach A, drawn over Figure 6, and its CSV files).

    Rerunnable and resumable: a step whose recorded result is complete and was made with the
    current settings and code is kept; missing, stale or incomplete ones are computed (the log
    says which is which); force recomputes every selected step.  findings.md always covers all
    figures: those not selected are taken from their recorded results when current, otherwise
    findings.md says they are missing.  Files of the output names that no recorded run made are
    not overwritten without force (refused before computing anything)."""
    config = config or ReproduceConfig.full()
    figures = tuple(sorted(set(int(f) for f in figures)))
    bad = [f for f in figures if f not in FIGURES]
    if bad:
        raise CrankgenError(f"figures must be among {', '.join(map(str, FIGURES))}; got {bad}")
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise OutputExistsError(f"{out} exists and is not a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
        if not os.access(out, os.W_OK | os.X_OK):
            raise PermissionError(13, "permission denied")
        lock = _Lock(out)
    except OSError as exc:          # before computing anything
        raise CrankgenError(f"cannot write to {out}: {exc.strerror or exc}") from None
    try:
        return _reproduce(out, config, force, quiet, figures, stream)
    finally:
        lock.release()


def _reproduce(out, config, force, quiet, figures, stream):
    ctx = Context(config, quiet=quiet, stream=stream)
    started = time.perf_counter()
    removed = remove_temporaries(out, all_files()) + remove_temporaries(out / DATA, all_files())
    if removed:
        ctx.log(f"removed {len(removed)} temporary file(s) left by an interrupted run: "
                + ", ".join(removed[:4]) + (" ..." if len(removed) > 4 else ""))
    manifest = Manifest.load(out, steps=STEPS, names=all_files())
    if manifest.entries and manifest.preset not in (None, config.preset):
        # a full and a quick run never replace each other silently
        if not force:
            raise OutputExistsError(
                f"{out} holds the results of a {manifest.preset} run of crankgen reproduce "
                f"(manifest.json); this {config.preset} run would replace them: choose another "
                "--out, or use --force to replace them")
        deleted = manifest.remove(list(manifest.entries))
        ctx.log(f"--force: the {manifest.preset} run recorded in {out} is replaced by this "
                f"{config.preset} run ({len(deleted)} of its files removed)")
    manifest.preset = config.preset
    # files this run may write that no recorded step made: refuse before computing anything
    selected = ["convergence check", *(["bifurcations", "exact rod"] if 6 in figures else []),
                *[f"figure {f}" for f in figures], "refinement check", "convergence files", "findings"]
    foreign = [n for s in selected for n in step_files(s)
               if (out / n).exists() and not manifest.owned(n)]
    if foreign and not force:
        names = [n for n in output_names(figures) if n in foreign] or foreign
        more = f" and {len(foreign) - 1} more" if len(foreign) > 1 else ""
        raise OutputExistsError(f"{out} already holds {names[0]}{more}, not made by a recorded "
                                "crankgen reproduce run of this folder; use --force to overwrite")
    version = run_version()
    written, kept, computed = [], [], []
    records = {"TransientCurve": F.TransientCurve}

    def run_step(step, settings, compute, write, recompute=False):
        """Keep the step if current (returns its recorded data), else compute, write, record."""
        state, reason = manifest.state(step, settings, version)
        if state == "current" and not (force or recompute):
            ctx.log(f"{step}: kept ({reason})")
            kept.append(step)
            return None
        why = "--force" if state == "current" else f"{state}: {reason}"
        if step not in ("convergence files", "findings"):
            ctx.start_engine()
        ctx.log(f"{step}: computing ({why})")
        files = step_files(step)
        manifest.start(step, settings, version, files)
        t0 = time.perf_counter()
        result = compute()
        write(result)
        manifest.finish(step, time.perf_counter() - t0)
        written.extend(f for f in files if not f.startswith(DATA + "/"))
        computed.append(step)
        return result

    def load(name):
        return read_json(out / DATA / name, records)

    # convergence check: the element counts of every figure
    conv_settings = _settings(config, ("paper_elements", "conv_ladder", "conv_omegas", "conv_tol"))
    conv = run_step("convergence check", conv_settings, lambda: F.convergence_study(ctx),
                    lambda c: write_json(out / DATA / "convergence.json", c))
    conv = conv if conv is not None else load("convergence.json")
    counts = conv["counts"]
    ctx.log("element counts used: " + ", ".join(f"{m} {a}: {n}" for (m, a), n in counts.items()))

    # bifurcations of approach A (drawn over Figure 6): computed with Figure 6, else the recorded
    # result when current
    bif_step = "bifurcations"
    bif_settings = _settings(config, _BIFURCATION_KEYS, runs=BF.settings_of(config, counts))

    def with_figure6(step, settings, compute, write, data):
        """(result, why missing) of a step computed with Figure 6: when Figure 6 is not selected,
        its recorded result (the JSON `data`) if complete and current, else None and the reason
        findings.md gives."""
        if 6 in figures:
            result = run_step(step, settings, compute, write)
            return (result if result is not None else load(data)), None
        state, reason = manifest.state(step, settings, version)
        if state == "current":
            ctx.log(f"{step}: not selected; its recorded result is used (complete and current)")
            return load(data), None
        missing = ({"missing": "not computed in this folder"}.get(state)
                   or f"its recorded result is {state} ({reason})")
        ctx.log(f"{step}: not selected and {missing}; findings.md says so")
        return None, missing

    def write_bifurcations(b):
        write_json(out / DATA / "bifurcations.json", b)
        for name, (cols, rows) in BF.tables(b).items():
            write_csv(out / name, cols, rows)
    bif, bif_missing = with_figure6(bif_step, bif_settings, lambda: BF.bifurcations(ctx, counts),
                                    write_bifurcations, "bifurcations.json")
    bif_print = manifest.fingerprint(bif_step) if bif is not None else None

    # the consistent model's special points re-read on the exact rod (exact_rod.py): with Figure 6,
    # else the recorded result when current
    exact_step = "exact rod"
    exact_settings = _settings(config, _EXACT_KEYS)

    def write_exact(x):
        from .plot_exact_rod import plot_exact_rod
        write_json(out / DATA / "exact_rod.json", x)
        for name, (cols, rows) in XR.tables(x).items():
            write_csv(out / name, cols, rows)
        save_figure(plot_exact_rod(x, config), out / "exact_rod.png", dpi=config.dpi)
    exact, exact_missing = with_figure6(exact_step, exact_settings, lambda: XR.exact_rod(ctx), write_exact,
                                        "exact_rod.json")

    funcs = {2: F.figure2, 3: F.figure3, 4: F.figure4, 5: F.figure5, 6: F.figure6,
             7: F.figure7, 8: F.figure8}
    data, missing, current = {}, {}, {}
    for f in FIGURES:
        step = f"figure {f}"
        extra = dict(bifurcations=bif_print) if f == 6 else {}
        settings = _settings(config, _FIGURE_KEYS[f], counts=_counts_list(counts), dpi=config.dpi,
                             **extra)
        if f in figures:
            def write_figure(d, f=f):
                write_json(out / DATA / f"fig{f}.json", d)
                write_csv(out / f"fig{f}.csv", *F.csv_table(d))
                save_figure(plots.plot_figure(d, config, counts, bifurcations=bif if f == 6 else None),
                            out / f"fig{f}.png", dpi=config.dpi)
            d = run_step(step, settings, lambda f=f: funcs[f](ctx, counts), write_figure)
            current[f] = True
            if d is not None:
                data[f] = d
        else:
            state, reason = manifest.state(step, settings, version)
            if state == "current":
                ctx.log(f"{step}: not selected; its recorded result is used (complete and current)")
                current[f] = True
            else:
                word = {"missing": "not computed in this folder"}.get(state, f"its recorded result is {state} ({reason})")
                ctx.log(f"{step}: not selected and {word}; findings.md lists it as missing")
                missing[f] = word

    def figure_data(f):
        if f not in data and current.get(f):
            data[f] = load(f"fig{f}.json")
        return data.get(f)

    refine = None
    if config.refine_omegas or config.refine_fig5:
        uses = {str(f): manifest.fingerprint(f"figure {f}") for f in (5, 6) if current.get(f)}
        settings = _settings(config, ("refine_omegas", "refine_fig5", "fig5_omegas", "fig5_eps",
                                      "fig6_eps"), counts=_counts_list(counts), reuses=uses)
        refine = run_step("refinement check", settings,
                          lambda: F.refinement_check(ctx, counts, figure_data(6), figure_data(5)),
                          lambda r: write_json(out / DATA / "refinement.json", r))
        refine = refine if refine is not None else load("refinement.json")
    elif "refinement check" in manifest.entries:
        # this configuration has no refinement check: a recorded one is not this run's result
        deleted = manifest.remove(["refinement check"])
        ctx.log("refinement check: not part of this configuration; the recorded one is removed "
                f"({', '.join(deleted) or 'no file left'})")
    inputs = {"convergence check": manifest.fingerprint("convergence check")}
    if refine is not None:
        inputs["refinement check"] = manifest.fingerprint("refinement check")

    def write_conv(_):
        write_csv(out / "convergence.csv", *F.convergence_table(conv, refine))
        save_figure(plots.plot_convergence(conv, config), out / "convergence.png", dpi=config.dpi)
    run_step("convergence files", dict(inputs=inputs, dpi=config.dpi, conv_tol=config.conv_tol),
             lambda: None, write_conv)

    for f in FIGURES:
        if current.get(f):
            inputs[f"figure {f}"] = manifest.fingerprint(f"figure {f}")
    if bif is not None:
        inputs[bif_step] = bif_print
    if exact is not None:
        inputs[exact_step] = manifest.fingerprint(exact_step)
    steps = ["convergence check", bif_step if bif is not None else None,
             exact_step if exact is not None else None,
             *[f"figure {f}" for f in FIGURES if current.get(f)],
             "refinement check" if refine is not None else None]
    timings = {s: manifest.wall_time(s) for s in steps if s}
    present = [n for n in output_names(FIGURES) if n != "findings.md"
               and (n.startswith("convergence") or (n in BIFURCATION_FILES and bif is not None)
                    or (n in EXACT_FILES and exact is not None)
                    or (n.startswith("fig") and int(n[3]) in current))]

    def make_findings():
        for f in FIGURES:
            figure_data(f)
        total = sum(v for v in timings.values() if v)
        return report.findings_markdown(config, conv, refine, data, timings, total, files=present,
                                        missing=missing, bifurcations=bif,
                                        bifurcations_missing=bif_missing, engine=ctx.engine,
                                        exact=exact, exact_missing=exact_missing)
    run_step("findings", dict(config=config.as_dict(), inputs=inputs, missing=missing,
                              bifurcations_missing=bif_missing, exact_missing=exact_missing),
             make_findings, lambda text: atomic_write_text(out / "findings.md", text))
    total = time.perf_counter() - started
    return dict(out=out, files=written, wall_time=total, data=data, convergence=conv,
                refinement=refine, bifurcations=bif, exact=exact, timings=timings, computed=computed, kept=kept,
                missing=missing)
