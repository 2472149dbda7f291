# floatfoam: the one entry point. `make run` (main job) and `make test` (tests) set up the
# machine themselves (apt + pinned .venv), idempotently.
SHELL := /bin/bash
.DEFAULT_GOAL := help

CASE ?= cylinder_heave
LEVEL ?= coarse
TIME_LEVEL ?= medium
# MPI ranks of a run; unset: floatfoam's default, this machine's cores up to 2 (`floatfoam run
# --help`), the one rule of run, validate and batch
NP ?=
SET ?=
PY := .venv/bin/python
FF := .venv/bin/floatfoam
SETARGS := $(foreach s,$(SET),--set $(s))
NPARGS := $(if $(NP),--np $(NP))
# the OpenFOAM and MPI environment is floatfoam's own (floatfoam.foam.runner.FOAM_ENV), set on
# every OpenFOAM command it starts: nothing to export here
export MPLBACKEND := Agg

# the CFD cases: `make <case>` runs one (LEVEL=coarse|medium|fine NP=n SET="..."); every folder
# of cases/ with a case.toml, but the shared ones whose names start with _
CFD_CASES := $(sort $(filter-out _%,$(patsubst cases/%/case.toml,%,$(wildcard cases/*/case.toml))))
.PHONY: $(CFD_CASES) help setup run test test-extended mesh mesh-table test-fast lint theory gz potential decay-model report validate pictures docs bench-theory bench-potential bench-cfd bench-sharing clean

help:  ## list the targets
	@grep -E '^[a-zA-Z_-]+:.*## ' $(MAKEFILE_LIST) | awk -F':.*## ' '{printf "  %-16s %s\n", $$1, $$2}'
	@echo "  CFD runs, one target per case (LEVEL=coarse|medium|fine NP=n, default the cores up to 2):"
	@for c in $(CFD_CASES); do echo "    make $$c"; done

setup:  ## install apt packages and the pinned .venv (idempotent)
	@bash scripts/setup.sh

run: setup  ## main job: the default case (Ito cylinder) at the coarse level, with its theory
	$(FF) run $(CASE) --level $(LEVEL) $(NPARGS) $(SETARGS)

$(CFD_CASES): setup
	$(FF) run $@ --level $(LEVEL) $(NPARGS) $(SETARGS)

test: setup  ## all tests but the extended ones (make test-extended): unit tests and the coarse OpenFOAM regression runs
	$(PY) -m pytest -q -m "not extended" -n 2 --dist worksteal --durations=15  # two workers, each running solver tests among the rest, the cores shared out (tests/conftest.py); ≤ 20 min on 2 cores, aim 15

test-extended: setup  ## the CFD checks beyond make test's 20 minutes (the 3D pitch decay ~1 min, the ellipsoid turning over ~11 min, a mesh made at rest ~1 min)
	$(PY) -m pytest -q -m extended --durations=5

test-fast: setup  ## unit tests only (no solver runs)
	$(PY) -m pytest -q -m "not openfoam and not slow"

lint: setup  ## ruff and shellcheck
	.venv/bin/ruff check src tests postprocess scripts meshes
	shellcheck scripts/*.sh .ci/run

theory: setup  ## theory of CASE (SET="mass.density=600 ..." to override)
	$(FF) theory $(CASE) $(SETARGS)

gz: setup  ## righting-arm curve of CASE, with a PNG in build/CASE/gz.png
	$(FF) gz $(CASE) $(SETARGS)

MODEL ?= cummins
potential: setup  ## added mass, radiation damping, periods with added mass of CASE (+ PNG)
	OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 $(FF) potential $(CASE) $(SETARGS) --plot

decay-model: setup  ## free-decay series of CASE, MODEL=linear|nonlinear|cummins [DOFS=heave,roll]
	OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 $(FF) decay-model $(CASE) --model $(MODEL) $(if $(DOFS),--dofs $(DOFS)) $(SETARGS)

bench-potential: setup  ## median mesh + BEM time (no cache) per case, 3 runs (3D ≤ 30 s, 2D ≤ 2 s)
	$(PY) scripts/bench_potential.py --threads $(or $(THREADS),2) $(CASES)

mesh: setup  ## body STL + gmsh fluid domain of CASE at LEVEL (coarse|medium|fine|all), checked
	$(FF) mesh body $(CASE) --level $(LEVEL) $(SETARGS)
	$(FF) mesh domain $(CASE) --level $(LEVEL) --check $(SETARGS)

mesh-table: setup  ## mesh levels table (Markdown) of every case, with checkMesh quality (minutes)
	$(FF) mesh table --domains --check

report: setup  ## gather every case (theory, potential flow, finished CFD runs) into build/report/
	$(FF) report

docs: setup  ## the documentation site (MkDocs Material, warnings are errors) in build/docs/site/
	$(PY) -m floatfoam.docsite

validate: setup  ## grid + time-step convergence (GCI) of CASE: coarse, medium, fine, medium with dt/2, coarse with its mesh motion spread (TIME_LEVEL=fine: fine with dt/2; MORPHING=F: the distances × F, default 1.5, or the Laplacian's 1/d; MORPHING=no: not run)
	$(FF) validate $(CASE) $(NPARGS) --time-level $(TIME_LEVEL) $(if $(filter no,$(MORPHING)),--no-morphing,$(if $(MORPHING),--morphing $(MORPHING))) $(SETARGS)

bench-cfd: setup  ## every CFD case, 1 s simulated (FULL=1: whole records; BASELINE=REV: that revision's run beside each): wall, steps, T_d, ζ, errors
	$(PY) scripts/bench_cfd.py --levels $(LEVEL) --ranks $(or $(RANKS),1 2) \
		--cases $(or $(CASES),$(CFD_CASES)) $(if $(FULL),--full) $(if $(BASELINE),--baseline $(BASELINE))

bench-sharing: setup  ## two runs at once on the cores against one alone (CASE, default cylinder_heave; 1 and 2 ranks)
	$(PY) scripts/bench_sharing.py --case $(or $(CASE),cylinder_heave) --ranks 1 2

bench-theory: setup  ## time `floatfoam theory` for every case (target ≤ 0.6 s median each)
	$(PY) scripts/bench_theory.py

pictures: setup  ## pictures of the flow of CASE's finished run at LEVEL, in build/CASE/pictures/LEVEL/
	$(FF) pictures $(CASE) --level $(LEVEL)

# the build folder's contents go, but build/solver (floatfoam's interFoam, which `make setup`
# builds in minutes); FLOATFOAM_BUILD names the build folder as for floatfoam, and is refused
# where emptying it would empty /, $HOME or the project
clean:  ## empty the build folder (build/, or FLOATFOAM_BUILD), keeping build/solver
	@build="$${FLOATFOAM_BUILD:-build}"; where="$$(realpath -m "$$build")"; \
	case "$$where" in /|"$$(realpath -m ~)"|"$$(realpath -m .)") \
		echo "make clean: FLOATFOAM_BUILD=$$build: valid is a build folder, not /, \$$HOME or the project" >&2; exit 2;; esac; \
	solver="$$(realpath -m build/solver)"; \
	if [ -d "$$build" ]; then \
		for entry in "$$build"/* "$$build"/.[!.]*; do \
			[ -e "$$entry" ] || [ -L "$$entry" ] || continue; \
			[ "$$(realpath -m "$$entry")" = "$$solver" ] || rm -rf -- "$$entry"; \
		done; \
	fi
