# Every routine command in one place. `make help` lists them.
VENV := .venv
PY := $(VENV)/bin/python
EXAMPLE ?= examples/office.txt
OUT ?= out

.PHONY: help setup demo serve test test-fast lint bench eval models clean

help:  ## list the targets
	@grep -E '^[a-z-]+:.*## ' Makefile | sed 's/:.*## /\t/'

setup:  ## apt packages (as root), .venv, pinned pip install, npm tools
	bash scripts/setup.sh

demo:  ## animate the example story into $(OUT)/
	$(VENV)/bin/wana animate $(EXAMPLE) -o $(OUT)

serve:  ## the web editor on http://127.0.0.1:8765
	$(VENV)/bin/wana serve

test:  ## the whole suite, slow tests included (what CI runs): pytest, then the editor's node tests
	$(PY) -m pytest -q
	cd editor && npm test --silent

test-fast:  ## skip tests marked slow
	$(PY) -m pytest -q -m "not slow"

lint:  ## ruff, mypy and the import contracts (services never import each other; see pyproject.toml)
	$(VENV)/bin/ruff check .
	$(VENV)/bin/ruff format --check .
	$(VENV)/bin/mypy proto services wana
	PYTHONPATH=. $(VENV)/bin/lint-imports

bench:  ## every benchmark, quick mode, JSON under bench/results/
	mkdir -p bench/results
	for b in bench/*.py; do $(PY) $$b --quick --json bench/results/$$(basename $$b .py).json || exit 1; done

eval:  ## every evaluation, quick mode, JSON under eval/results/
	mkdir -p eval/results
	for e in eval/*.py; do $(PY) $$e --quick --json eval/results/$$(basename $$e .py).json || exit 1; done

models:  ## rebuild every committed model and generated asset (needs ../shared/data; about 40 min on 2 cores)
	$(PY) scripts/train_nlp.py --force
	OMP_NUM_THREADS=1 nice -n 10 $(PY) -m services.motion.train_locomotion
	$(PY) -m tools.authoring.author_actions
	$(PY) -m wana.assets.scenedb --per-room 10
	$(PY) -m tools.authoring.build_vad

clean:
	rm -rf $(OUT) .pytest_cache .ruff_cache .mypy_cache .import_linter_cache
