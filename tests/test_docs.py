"""The documentation site (docs/, `make docs`): it builds with no warning (every tutorial block and
gallery example runs, every public name is documented, every cross-reference resolves), every
local link of the built site points to a file and an anchor that exist, the generated reference
lists every command, option and CSV column the program has, a fault of each kind fails the build,
and three pages opened in headless Chromium show their title and their figure.

The site is built from a copy of docs/ in the test's own folder (the build writes generated pages
and the gallery into its source folder). Under CI the documentation's tools and Chromium must be
installed (.ci/run installs them); elsewhere their absence skips these tests.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import numpy as np
import pytest

import crankgen

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
GENERATED = ("_build", "_generated", "gallery", "__pycache__")   # made by a build, never copied

pytestmark = pytest.mark.slow


def _require(module):
    try:
        __import__(module)
    except ImportError:
        if os.environ.get("CI"):
            raise
        pytest.skip(f"{module} is not installed (pip install -e '.[docs]')")


def _copy_docs(dest):
    shutil.copytree(DOCS, dest, ignore=shutil.ignore_patterns(*GENERATED))
    return dest


def _build(source, out, cwd):
    return subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", "-q",
                           "-d", str(out.parent / "doctrees"), str(source), str(out)],
                          cwd=cwd, capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The whole site built once: (the html folder, the build's output)."""
    _require("sphinx")
    _require("myst_parser")
    _require("sphinx_gallery")
    work = tmp_path_factory.mktemp("docs")
    source = _copy_docs(work / "docs")
    out = work / "html"
    done = _build(source, out, work)
    return out, done


def test_the_site_builds_with_no_warning(site):
    out, done = site
    log = done.stdout + done.stderr
    assert done.returncode == 0, log[-6000:]
    assert "WARNING" not in log and "ERROR" not in log, log[-6000:]
    for page in ("index.html", "tutorial/designer-study.html", "reference/api.html", "reference/cli.html",
                 "reference/columns.html", "errata.html", "validation.html", "gallery/index.html"):
        assert (out / page).is_file(), page


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("name"):
            self.ids.add(attrs["name"])
        for key in ("href", "src"):
            if attrs.get(key):
                self.links.append(attrs[key])


def _parse(path):
    parser = _Links()
    parser.feed(path.read_text(encoding="utf-8"))
    return parser


def test_every_local_link_of_the_site_resolves(site):
    """Every href and src of every page that is not a web address points to a file of the site,
    and its #anchor to an id of that page."""
    out, _ = site
    pages = {p: _parse(p) for p in out.rglob("*.html")}
    assert len(pages) > 30
    broken = []
    for page, parsed in pages.items():
        for link in parsed.links:
            parts = urlsplit(link)
            if parts.scheme or link.startswith("//") or link.startswith("data:"):
                continue
            target = (page.parent / unquote(parts.path)).resolve() if parts.path else page
            if not target.exists():
                broken.append(f"{page.relative_to(out)}: {link}")
                continue
            if parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else _parse(target).ids
                if unquote(parts.fragment) not in ids:
                    broken.append(f"{page.relative_to(out)}: {link} (no such anchor)")
    assert not broken, "\n".join(broken[:40])


def test_every_public_name_is_in_the_api_reference(site):
    out, _ = site
    ids = _parse(out / "reference" / "api.html").ids
    missing = [name for name in crankgen.__all__ if f"crankgen.{name}" not in ids and f"module-crankgen.{name}" not in ids]
    assert not missing, missing


def test_the_reference_lists_every_command_option_and_column(site):
    """The generated pages hold what the program has: every command and option of the parser,
    every declared output and every column of a steady state's row."""
    out, _ = site
    from crankgen.declaration import schema
    from crankgen.cli import build_parser
    from crankgen.results.steady_row import RESULTS, MOTOR_RESULTS

    cli = (out / "reference" / "cli.html").read_text(encoding="utf-8")
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    for name, command in sub.choices.items():
        assert f'id="crankgen-{name}"' in cli, name
        for action in command._actions:
            for flag in action.option_strings:
                assert flag in cli, (name, flag)
    columns = (out / "reference" / "columns.html").read_text(encoding="utf-8")
    for name in list(schema.OUTPUTS) + list(schema.PARAMETERS) + [r[0] for r in RESULTS + MOTOR_RESULTS]:
        assert f"<code class=\"docutils literal notranslate\"><span class=\"pre\">{name}" in columns, name


INDEX = """\
# A small site

{fault}

```{{toctree}}
gallery/index
```
"""

FAILING_EXAMPLE = '''\
"""
An example that fails
=====================
"""
raise RuntimeError("this example fails on purpose")
'''

FAULTS = {  # fault: (what the index says, the gallery's example or None, what the build must say)
    "a broken link": ("[a page that does not exist](nowhere.md)", None, "nowhere.md"),
    "a failing example": ("", FAILING_EXAMPLE, "this example fails on purpose"),
    "a missing API entry": ("", None, "does not document crankgen.simulate"),
}


@pytest.mark.parametrize("fault", list(FAULTS))
def test_a_fault_fails_the_build(fault, tmp_path):
    """The site's own configuration on a small site with one fault: a page with a broken link, a
    gallery example that raises, or no API reference (every site but the full one lacks it): the
    build fails and names the fault."""
    _require("sphinx")
    text, example, message = FAULTS[fault]
    source = tmp_path / "docs"
    source.mkdir()
    for name in ("conf.py", "_ext", "_static"):
        src = DOCS / name
        (shutil.copytree if src.is_dir() else shutil.copy)(src, source / name)
    (source / "index.md").write_text(INDEX.format(fault=text))
    (source / "examples").mkdir()
    (source / "examples" / "GALLERY_HEADER.rst").write_text("Gallery\n=======\n")
    if example:
        (source / "examples" / "plot_example.py").write_text(example)
    done = _build(source, tmp_path / "html", tmp_path)
    log = done.stdout + done.stderr
    assert done.returncode != 0, log[-3000:]
    assert message in log, log[-3000:]


# ---- the pages in a browser ----------------------------------------------------------------------

PAGES = [  # (page, its title, the figure it must show)
    ("index.html", "crankgen", "_images/index-1-0.png"),
    ("tutorial/continuation.html", "A continuation and its bifurcation diagram", "_images/tutorial-continuation-1-0.png"),
    ("gallery/plot_stability_chart.html", "A stability chart", "_images/sphx_glr_plot_stability_chart_001.png"),
]

GEOMETRY = """JSON.stringify((() => {
  const box = e => { const r = e.getBoundingClientRect();
                     return [r.left + scrollX, r.top + scrollY, r.width, r.height]; };
  const h1 = document.querySelector('div.body h1, article h1, h1');
  const img = [...document.images].find(i => i.getAttribute('src').endsWith(%r));
  return {title: h1 ? h1.textContent.replace('\\u00b6', '').trim() : null, h1: h1 ? box(h1) : null,
          img: img ? box(img) : null, loaded: img ? img.complete && img.naturalWidth > 0 : false};
})())"""


def _crop(image, box):
    x, y, w, h = (int(round(v)) for v in box)
    return image.crop((x, y, x + w, y + h))


def test_three_pages_show_their_title_and_figure_in_chromium(site, tmp_path):
    """Front page, a tutorial page and a gallery page in headless Chromium: the screenshot holds
    the page's title (dark text pixels in its heading's box) and its figure (the pixels in the
    image's box are the figure's PNG, scaled: correlation above 0.9)."""
    import json

    from PIL import Image

    from browser import Browser, chromium

    if chromium() is None:
        if os.environ.get("CI"):
            pytest.fail("chromium is not installed: .ci/run installs it (apt-get install chromium)")
        pytest.skip("chromium is not installed")
    out, done = site
    assert done.returncode == 0
    keep = os.environ.get("CRANKGEN_DOCS_SCREENSHOTS")       # a folder to keep the screenshots in
    with Browser(tmp_path / "profile") as browser:
        for page, title, figure in PAGES:
            browser.open((out / page).as_uri())
            geometry = json.loads(browser.evaluate(GEOMETRY % Path(figure).name))
            shot = tmp_path / (page.replace("/", "-").replace(".html", ".png"))
            browser.screenshot(shot)
            if keep:
                Path(keep).mkdir(parents=True, exist_ok=True)
                shutil.copy(shot, Path(keep) / shot.name)
            assert geometry["title"] == title, (page, geometry["title"])
            assert geometry["img"] is not None and geometry["loaded"], (page, figure)
            screen = Image.open(shot).convert("L")
            heading = np.asarray(_crop(screen, geometry["h1"]), dtype=float)
            assert heading.size and np.mean(heading < 110) > 0.02, f"{page}: no title drawn in its heading's box"
            shown = np.asarray(_crop(screen, geometry["img"]), dtype=float)
            source = Image.open(out / figure).convert("L").resize(shown.shape[::-1], Image.LANCZOS)
            source = np.asarray(source, dtype=float)
            assert shown.std() > 10, f"{page}: the figure's box is blank"
            r = np.corrcoef(shown.ravel(), source.ravel())[0, 1]
            assert r > 0.9, f"{page}: the screenshot's figure is not {figure} (correlation {r:.2f})"


# ---- the README's links ----------------------------------------------------------------------------

def test_the_readmes_links_point_to_files_of_the_repository():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    links = re.findall(r"\]\(([^)\s]+)\)", readme)
    local = [unquote(urlsplit(link).path) for link in links if not urlsplit(link).scheme]
    assert local and all((ROOT / path).exists() for path in local), [p for p in local if not (ROOT / p).exists()]
    assert len(readme.splitlines()) <= 250
