"""The record of a reproduce folder (manifest.json): a manifest without the expected shape is
treated as absent (a warning naming the file, never a traceback), a malformed step record as a
step not computed; a full and a quick run never replace each other without --force, and the
manifest holds only what this folder's run made."""

import json
import warnings

import pytest

from crankgen.cli import main as cli_main
from crankgen.experiments import ReproduceConfig, reproduce
from crankgen.experiments.manifest import Manifest, ManifestWarning
from crankgen.experiments.runner import STEPS, all_files

SHA = "0" * 64
GOOD_STEP = {"state": "complete", "settings": {}, "code_version": {}, "files": {"fig8.csv": SHA},
             "wall_time": 1.0}


def _doc(steps):
    return {"format": 1, "steps": steps}


# every shape a hand-edited or truncated manifest.json may have, and what must survive of it
MALFORMED_DOCUMENTS = {
    "a list": [],
    "null": None,
    "a number": 3,
    "a string": "manifest",
    "not JSON": "{\"format\": 1, \"steps\": {",
    "no steps": {"format": 1},
    "steps a list": {"format": 1, "steps": [GOOD_STEP]},
    "another format": {"format": 99, "steps": {}},
    "preset a number": {"format": 1, "preset": 4, "steps": {}},
}
MALFORMED_STEPS = {
    "a step that is a string": "complete",
    "a step that is a list": [GOOD_STEP],
    "files as a list": dict(GOOD_STEP, files=["fig8.csv"]),
    "files null": dict(GOOD_STEP, files=None),
    "a hash that is a number": dict(GOOD_STEP, files={"fig8.csv": 12}),
    "a file outside the outputs": dict(GOOD_STEP, files={"../../etc/passwd": SHA}),
    "an unknown state": dict(GOOD_STEP, state="done"),
    "settings a list": dict(GOOD_STEP, settings=[]),
    "wall time a string": dict(GOOD_STEP, wall_time="1 s"),
}


def _write(folder, doc):
    text = doc if isinstance(doc, str) and doc.startswith("{") else json.dumps(doc)
    (folder / "manifest.json").write_text(text)


@pytest.mark.parametrize("shape", sorted(MALFORMED_DOCUMENTS))
def test_a_malformed_manifest_is_absent_with_a_warning(tmp_path, shape):
    _write(tmp_path, MALFORMED_DOCUMENTS[shape])
    with pytest.warns(ManifestWarning, match="manifest.json is not a crankgen reproduce manifest"):
        m = Manifest.load(tmp_path, steps=STEPS, names=all_files())
    assert m.entries == {} and not m.owned("fig8.csv")
    assert m.state("figure 8", {}, {}) == ("missing", "not computed yet")


@pytest.mark.parametrize("shape", sorted(MALFORMED_STEPS))
def test_a_malformed_step_record_is_a_step_not_computed(tmp_path, shape):
    _write(tmp_path, _doc({"figure 8": MALFORMED_STEPS[shape], "figure 7": GOOD_STEP,
                           "no such step": GOOD_STEP}))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        m = Manifest.load(tmp_path, steps=STEPS, names=all_files())
    texts = [str(w.message) for w in caught if issubclass(w.category, ManifestWarning)]
    assert any("'figure 8' is malformed" in t and "manifest.json" in t for t in texts), texts
    assert any("'no such step'" in t for t in texts), texts
    assert list(m.entries) == ["figure 7"]
    assert m.state("figure 8", {}, {})[0] == "missing"


@pytest.mark.parametrize("shape", sorted(MALFORMED_DOCUMENTS) + sorted(MALFORMED_STEPS))
def test_reproduce_over_a_malformed_manifest_recovers(tmp_path, capsys, monkeypatch, shape):
    """The issue's command, `crankgen reproduce --quick --force` (the tiny preset standing in for
    the quick one), over each malformed manifest: a one-line warning naming the file, no
    traceback, a complete run.  (The tiny preset without the refinement check, which the quick
    preset does not make either: QUICK below.)"""
    monkeypatch.setattr(ReproduceConfig, "quick", classmethod(lambda cls: QUICK))
    out = tmp_path / "r"
    out.mkdir()
    doc = MALFORMED_DOCUMENTS.get(shape) or _doc({"figure 8": MALFORMED_STEPS.get(shape)})
    _write(out, doc)
    assert cli_main(["reproduce", "--quick", "--force", "--figures", "8", "--out", str(out),
                     "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "Traceback" not in err and "crankgen: warning:" in err and str(out / "manifest.json") in err
    steps = json.loads((out / "manifest.json").read_text())["steps"]
    assert steps["figure 8"]["state"] == "complete" and steps["findings"]["state"] == "complete"


def test_without_force_a_malformed_manifest_does_not_own_the_files_beside_it(tmp_path, capsys):
    out = tmp_path / "r"
    out.mkdir()
    _write(out, [])
    (out / "fig8.csv").write_text("some table\n")
    assert cli_main(["reproduce", "--figures", "8", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "manifest.json is not a crankgen reproduce manifest" in err
    assert "fig8.csv" in err.strip().splitlines()[-1] and "--force" in err
    assert (out / "fig8.csv").read_text() == "some table\n"


# ----------------------------------------------------------------------------- full and quick

FULL = ReproduceConfig.tiny().with_(preset="full")
QUICK = ReproduceConfig.tiny().with_(preset="quick", refine_omegas=(), refine_fig5=False)


def test_full_and_quick_never_replace_each_other_without_force(tmp_path, capsys, monkeypatch):
    """A full run's folder refuses a quick run (and back) without --force.  The refusal reads the
    manifest's preset before any step runs, whatever figures are asked for: Figure 8 alone (with
    the convergence and refinement checks and the findings every run makes) stands for them all."""
    monkeypatch.setattr(ReproduceConfig, "full", classmethod(lambda cls: FULL))
    monkeypatch.setattr(ReproduceConfig, "quick", classmethod(lambda cls: QUICK))
    out = tmp_path / "r"
    assert cli_main(["reproduce", "--figures", "8", "--out", str(out), "--quiet"]) == 0
    assert (out / "data" / "refinement.json").exists()
    before = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    capsys.readouterr()

    assert cli_main(["reproduce", "--quick", "--figures", "8", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "a full run" in err[0] and "--force" in err[0] and "--out" in err[0]
    assert {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()} == before

    assert cli_main(["reproduce", "--quick", "--force", "--figures", "8", "--out", str(out), "--quiet"]) == 0
    doc = json.loads((out / "manifest.json").read_text())
    assert doc["preset"] == "quick" and "refinement check" not in doc["steps"]
    assert not (out / "data" / "refinement.json").exists()
    assert all(e["state"] == "complete" for e in doc["steps"].values())
    text = (out / "findings.md").read_text()
    assert "preset `quick`" in text and "| refinement check (2 n elements) | not run |" in text

    assert cli_main(["reproduce", "--figures", "8", "--out", str(out), "--quiet"]) == 2     # and back: refused too
    assert "a quick run" in capsys.readouterr().err


def test_a_step_the_configuration_does_not_have_leaves_the_manifest(tmp_path):
    """The same preset with the refinement check switched off (a caller's own configuration):
    the recorded refinement check and its data are removed, so the manifest says what findings.md
    says."""
    out = tmp_path / "r"
    reproduce(out, config=FULL, quiet=True, figures=[8])
    assert json.loads((out / "manifest.json").read_text())["steps"]["refinement check"]["state"] == "complete"
    reproduce(out, config=FULL.with_(refine_omegas=(), refine_fig5=False), quiet=True, figures=[8])
    doc = json.loads((out / "manifest.json").read_text())
    assert "refinement check" not in doc["steps"] and not (out / "data" / "refinement.json").exists()
    assert "| refinement check (2 n elements) | not run |" in (out / "findings.md").read_text()
