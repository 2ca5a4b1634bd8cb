# The project's virtual environment when there is one (README: python3 -m venv .venv ...), so that
# `make test` finds the test dependencies without activating it; `make PYTHON=...` overrides.
PYTHON ?= $(if $(wildcard .venv/bin/python),.venv/bin/python,python3)

.PHONY: derive check-generated test bench audit validate docs docs-clean

# derive/ reads crankgen's records (src/crankgen), never generated/: no install is needed
DERIVE = PYTHONPATH=src$${PYTHONPATH:+:$$PYTHONPATH} $(PYTHON) -m derive

derive:            ## regenerate generated/ from the SymPy derivation in derive/
	$(DERIVE)

check-generated:   ## fail if generated/ differs from what derive/ produces (changed, new or missing files)
	$(DERIVE) --check

test:              ## the test suite (the README's test command without the install)
	$(PYTHON) -m pytest -q

bench:             ## benchmark: writes bench/results.json and prints a table
	$(PYTHON) bench/run.py

audit:             ## symbolic audit report: audit/report.md
	$(PYTHON) -m crankgen.cli audit --out audit

validate:          ## optional: compare with Exudyn's ANCF cable model, amplitudes and time per step (installs exudyn)
	$(PYTHON) -m pip install exudyn && $(PYTHON) validate/compare.py

docs:              ## the documentation site: docs/_build/html (warnings are errors; runs the gallery)
	$(PYTHON) -m sphinx -W --keep-going -b html -j 1 docs docs/_build/html

docs-clean:        ## remove what make docs generates (the site, the gallery's pages, the generated reference)
	rm -rf docs/_build docs/gallery docs/_generated docs/reference/_generated
