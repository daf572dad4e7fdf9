# The two commands of the README: `make demo` and `make test`. Each installs what is missing
# (Debian packages, only when absent), configures, builds and runs.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
# Debian's python3 (h5py, numpy, matplotlib, yaml); the package gran (python/gran) is found through
# PYTHONPATH, the one mechanism everywhere (CTest and `gran tradeoff` set it too).
PY := PYTHONPATH=$(CURDIR)/python /usr/bin/python3
DEB_PACKAGES := cmake g++ ninja-build pkg-config libeigen3-dev libboost-dev libhdf5-dev libfmt-dev \
  libspdlog-dev libyaml-cpp-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev \
  python3-h5py python3-numpy python3-matplotlib python3-yaml pybind11-dev python3-dev python3-pytest \
  python3-mdanalysis paraview libopenmpi-dev openmpi-bin
# Warnings are errors in CI (CI=true) and whenever GRAN_WERROR=ON is given.
GRAN_WERROR ?= $(if $(CI),ON,OFF)
CMAKE_FLAGS ?=

.PHONY: fuzz deps configure build demo test test-cluster docs validate bench bench-peers format sanitize clean reproduce-barrat-trizac-2002 \
  reproduce-mcnamara-falcon-2005 reproduce-bhateja-2016 tradeoff

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "gran: installing missing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -eq 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	fi

configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DGRAN_WERROR=$(GRAN_WERROR) $(CMAKE_FLAGS) >/dev/null

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	@mkdir -p results/demo
	$(BUILD_DIR)/gran run studies/demo/vibrated-mixture-2d.yaml -o results/demo/vibrated-mixture-2d.h5
	$(PY) studies/plot_result.py results/demo/vibrated-mixture-2d.h5 -o results/demo/vibrated-mixture-2d.png
	@echo "demo: results in results/demo/"

# The suite, then the SLURM cluster test (about a minute, needs root to start slurmctld, slurmd
# and munge; `make test TEST_CLUSTER=0` leaves it out where that is impossible).
TEST_CLUSTER ?= 1
test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE validate
ifeq ($(TEST_CLUSTER),1)
	@$(MAKE) --no-print-directory test-cluster
endif

# docs/scene-reference.md is generated from the declarations in the code (schemas, summaries,
# descriptions); Docs.SceneReferenceIsUpToDate fails when the committed copy is stale.
docs: build
	$(BUILD_DIR)/gran list --markdown > docs/scene-reference.md.tmp && \
	  mv docs/scene-reference.md.tmp docs/scene-reference.md || { rm -f docs/scene-reference.md.tmp; exit 1; }

validate: build
	cd $(BUILD_DIR) && ctest --output-on-failure -L validate

# gran_bench_features: what each scene feature costs against the bare gas, and the bare gas
# against a minimal specialised kernel (about 10 min; docs/performance.md).
bench: build
	@mkdir -p results
	$(BUILD_DIR)/gran_bench --csv results/bench.csv
	$(BUILD_DIR)/gran_bench_dem --csv results/bench.csv | tee results/bench_dem.txt
	$(BUILD_DIR)/gran_bench_features --csv results/feature_cost.csv | tee results/feature_cost.txt

# gran against its peers side by side, one core each (bench/peers.sh; about 15 min): Smallenburg's
# EDMD when EDMD=/path/to/a clone of github.com/FSmallenburg/EDMD is given (built from that path,
# never copied here), LAMMPS and LIGGGHTS from Debian (installed when absent) on the vibrated and
# the settled bed. ROUNDS, EDMD_PHIS, EDMD_NS, DEM_SIZES, SETTLED_SIZES pass through.
PEER_PACKAGES := lammps liggghts
bench-peers: build
	@$(MAKE) --no-print-directory deps DEB_PACKAGES="$(PEER_PACKAGES)"
	EDMD=$(EDMD) bench/peers.sh

# A study on a real single-node SLURM cluster (issue 18, docs/cluster.md): Debian's slurmctld,
# slurmd and munge on localhost (root), a job array with one task stopped by the time-limit
# warning and resubmitted, the merged results against a local run. About a minute.
CLUSTER_PACKAGES := slurmctld slurmd slurm-client munge
test-cluster: build
	@$(MAKE) --no-print-directory deps DEB_PACKAGES="$(CLUSTER_PACKAGES)"
	tests/cluster/test_slurm_study.sh $(BUILD_DIR)

# Barrat & Trizac 2002: Tables I-II and Figs. 1-4, 6-9, 13-17 (36 runs on all cores, about 8 min
# on 2 cores; completed runs are reused). Writes results/barrat-trizac-2002/{figN,tables}.png,
# comparison.csv (paper vs measured) and claims.csv (the paper's qualitative statements, checked).
BT2002_STUDIES := tables monodisperse mixture
BT2002_OUT ?= results/barrat-trizac-2002
reproduce-barrat-trizac-2002: build
	for s in $(BT2002_STUDIES); do \
	  $(BUILD_DIR)/gran study studies/barrat-trizac-2002/$$s.yaml -o $(BT2002_OUT) || exit 1; \
	done
	$(PY) studies/barrat-trizac-2002/figures.py $(BT2002_OUT)

# McNamara & Falcon 2005: Figs. 1-4 (sweep.yaml: 440 runs, about 3 CPU minutes, so about 1.5 min
# on two free cores; snapshots.yaml: 2 runs, about 1 s; completed runs are reused, then about
# 5 s). Writes results/mcnamara-falcon-2005/fig{1,2,3,4}.png and comparison.csv (paper vs measured).
MF2005_STUDIES := sweep snapshots
MF2005_OUT ?= results/mcnamara-falcon-2005
reproduce-mcnamara-falcon-2005: build
	for s in $(MF2005_STUDIES); do \
	  $(BUILD_DIR)/gran study studies/mcnamara-falcon-2005/$$s.yaml -o $(MF2005_OUT) || exit 1; \
	done
	$(PY) studies/mcnamara-falcon-2005/figures.py $(MF2005_OUT)

# Bhateja, Sharma & Singh 2016: Figs. 2, 4, 5, 6-16 and Tables I-III (about 430 runs, about 1.5 h on 2
# cores; completed runs are reused, then about 6 s). Writes results/bhateja-2016/comparison.csv
# (paper vs measured, studies/bhateja-2016/analysis.py) and figures/*.png (figures.py).
BH2016_STUDIES := rest-2d rest-3d sweep-2d sweep-3d lid-g0 engines-2d sensitivity-3d amplitude-2d \
  parameters-2d profiles-3d ct-scan-3d fig5 channel-full-3d
BH2016_OUT ?= results/bhateja-2016
reproduce-bhateja-2016: build
	for s in $(BH2016_STUDIES); do \
	  $(BUILD_DIR)/gran study studies/bhateja-2016/$$s.yaml -o $(BH2016_OUT) || exit 1; \
	done
	$(PY) studies/bhateja-2016/analysis.py $(BH2016_OUT)
	$(PY) studies/bhateja-2016/figures.py $(BH2016_OUT)

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

# UBSan recovers by default: a report in a passing test (or in a gran run a test starts and whose
# output it keeps) would go unseen. halt_on_error makes every report fail its test.
sanitize:
	UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	  $(MAKE) test BUILD_DIR=build-asan CMAKE_FLAGS="-DGRAN_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo"

# Fuzzing campaign of the scene loader under ASan and UBSan (tests/fuzz/fuzz_scenes.cpp): mutants of
# every scene of the project for FUZZ_SECONDS; failing inputs go to results/fuzz/. The in-suite
# run (fixed seed, 20000 mutants) is SceneLoaderFuzz in `make test`.
FUZZ_SECONDS ?= 600
FUZZ_SEED ?= 1
fuzz:
	$(MAKE) configure BUILD_DIR=build-asan CMAKE_FLAGS="-DGRAN_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo"
	cmake --build build-asan -j $(JOBS) --target gran_fuzz_scenes
	UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 build-asan/tests/gran_fuzz_scenes --seconds $(FUZZ_SECONDS) --seed $(FUZZ_SEED) \
	  --findings results/fuzz .

clean:
	rm -rf $(BUILD_DIR) build-asan

# Speed versus accuracy (issue #6, docs/choosing-speed-or-accuracy.md): `gran tradeoff` on the
# Bhateja 3D rough bed and its frictionless twin (W = 20), the frictionless bed on a grid of k_n and
# dt/t_c against the event-driven engine, the Barrat & Trizac Table I vibrated
# mixture and the heated mixture (analytic reference: the Maxwellian theory). About 15 CPU minutes;
# completed runs are reused. Writes results/tradeoff/<case>/<scene>.{tradeoff.md,tradeoff.csv,
# tradeoff.png,study.h5}.
TRADEOFF_OUT ?= results/tradeoff
BH3D_W20 := --set drivers.0.frequency=0.711763 --set run.sample_interval=0.192901 \
  --quantity observables.local_temperature.T_z_volume_scaled \
  --quantity observables.local_temperature.T_z_plain_scaled \
  --quantity observables.barycentric_height.h_cm
tradeoff: build
	$(BUILD_DIR)/gran tradeoff studies/bhateja-2016/canonical-3d.yaml --set interactions.friction=0.4 \
	  $(BH3D_W20) -o $(TRADEOFF_OUT)/bhateja-3d-rough
	$(BUILD_DIR)/gran tradeoff studies/bhateja-2016/canonical-3d.yaml --set interactions.friction=0 \
	  $(BH3D_W20) -o $(TRADEOFF_OUT)/bhateja-3d-smooth
	$(BUILD_DIR)/gran study studies/tradeoff/dem-convergence-3d.yaml -o $(TRADEOFF_OUT)/dem-convergence-3d
	$(BUILD_DIR)/gran tradeoff studies/barrat-trizac-2002/vibrated-mixture.yaml \
	  -o $(TRADEOFF_OUT)/barrat-trizac-table1
	$(BUILD_DIR)/gran tradeoff studies/demo/binary-thermostat-2d.yaml \
	  --analytic observables.temperatures.ratios.light_over_heavy.gamma=0.7459 \
	  -o $(TRADEOFF_OUT)/heated-mixture
