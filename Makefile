# Two commands do everything on a fresh machine:
#   make demo   -- set up .venv, then run the main job on the built-in default
#   make test   -- set up .venv, then run the test suite (fast default; `make test-all` adds slow tests)
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

RUNTIME_VENV := .venv-runtime

.PHONY: demo test test-all test-runtime lint bench clean gpu-wheels gpu-check

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	# torchvision's wheels need the CUDA build of torch (the CPU-only wheel cannot load its ops);
	# the default PyPI torch is that build and runs on CPU where there is no GPU.
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/radaraug reproduce --quick --resume -o demo_out

test: $(STAMP)
	$(PY) -m pytest -q

test-all: $(STAMP)
	$(PY) -m pytest -q -m ''

# A second virtualenv with only the declared runtime dependencies (`pip install .`, no [test]
# extra): the CLI starts, the twin simulates 16 frames, and the convex-room fast path is on (it
# needs scipy; without it the twin would run ~1.7x slower with the same output). Not part of
# `make test` (it downloads and installs every dependency); CI runs it as its own job.
test-runtime:
	rm -rf $(RUNTIME_VENV)
	$(PYTHON) -m venv $(RUNTIME_VENV)
	$(RUNTIME_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(RUNTIME_VENV)/bin/python -m pip install --quiet .
	.ci/runtime-check $(RUNTIME_VENV)/bin/radaraug

lint: $(STAMP)
	$(VENV)/bin/ruff check radaraug tests

bench: $(STAMP)
	$(VENV)/bin/radaraug bench transforms -o benchmarks/transforms_cpu.json --overwrite
	$(VENV)/bin/radaraug bench twin -o benchmarks/twin_cpu.json --overwrite
	$(VENV)/bin/radaraug bench items -o benchmarks/twin_items_cpu.json --overwrite
	$(VENV)/bin/radaraug bench training -o benchmarks/training_cpu.json --overwrite
	$(VENV)/bin/radaraug bench diagnose -o benchmarks/diagnose_cpu.json --overwrite
	$(VENV)/bin/radaraug bench steps -o benchmarks/steps_cpu.json --overwrite
	$(VENV)/bin/radaraug bench static-room -o benchmarks/static_room_cpu.json --overwrite --figure docs/img/twin/static_profile_vs_density.png

# GPU checks (docs/gpu.md). `make gpu-wheels` (a machine with internet) downloads the wheels a GPU
# machine with Python 3.12, PyTorch, torchvision, Lightning, h5py, matplotlib, scipy and tqdm lacks;
# `make gpu-check` (on the GPU machine, the repository and gpu_wheels/ copied there) installs them and
# the package and runs the CUDA tests, benchmarks and a GPU reproduce, all output in gpu_check_out/.
GPU_PYTHON ?= python3
GPU_WHEELS := trimesh==5.2.0 pyusb==1.3.1 jsonargparse==4.53.0 docstring_parser==0.18.0 \
	typeshed_client==2.15.0 setuptools==84.2.1

gpu-wheels:
	$(PYTHON) -m pip download --no-deps --only-binary=:all: --python-version 3.12 --implementation cp \
		--platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 --platform manylinux2014_x86_64 \
		-d gpu_wheels $(GPU_WHEELS)

gpu-check:
	$(GPU_PYTHON) scripts/gpu_check.py --out gpu_check_out $(GPU_CHECK_ARGS)

clean:
	rm -rf $(VENV) $(RUNTIME_VENV) demo_out build *.egg-info gpu_check_out
