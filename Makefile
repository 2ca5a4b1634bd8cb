PYTHON ?= python3

.PHONY: derive check-generated test bench

derive:            ## regenerate generated/ from the SymPy derivation in derive/
	$(PYTHON) -m derive

check-generated:   ## fail if generated/ differs from what derive/ produces (changed, new or missing files)
	$(PYTHON) -m derive --check

test:
	$(PYTHON) -m pytest -q

bench:             ## benchmark: writes bench/results.json and prints a table
	$(PYTHON) bench/run.py
