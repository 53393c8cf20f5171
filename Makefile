# granflow — the two commands: `make run` and `make test`.
# Everything else goes through CMake; this file only sequences it.
BUILD      ?= build
BUILD_SAN  ?= build-san
BUILD_FUZZ ?= build-fuzz
BUILD_MPI  ?= build-mpi
FUZZ_SECONDS ?= 60
FUZZ_TEST_SECONDS ?= 3
GF_WERROR  ?= OFF
RUN_DIR    ?= runs/silo
RUN_TAU    ?= 40
RUN_ENGINE ?= --set run.mode=fixed --set run.order=spatial --set run.threads=0
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

.PHONY: all deps build build-cli build-san build-fuzz build-mpi run test test-fast test-san test-fuzz test-mpi fuzz bench bench-dem reproduce clean

all: build

# Sub-makes (cmake's generated Makefiles) without "Entering directory" lines.
MAKEFLAGS += --no-print-directory
CONFIGURE = -DCMAKE_BUILD_TYPE=Release -DGF_WERROR=$(GF_WERROR) $(CMAKE_ARGS)

deps:
	@bash scripts/deps.sh

# scripts/build.sh configures quietly and shows one progress line (logs in
# BUILD/configure.log and BUILD/build.log; warnings and errors shown whole).
# Everything: the library, the CLI, the test suites and fuzz replays (make test).
build: deps
	@bash scripts/build.sh $(BUILD) $(JOBS) "$(CONFIGURE)"

# The CLI and the library it links, no test executable: what run, bench and
# reproduce need (tests/cli/make_run.sh checks `make -n run` builds no test).
build-cli: deps
	@bash scripts/build.sh $(BUILD) $(JOBS) "$(CONFIGURE)" granflow_cli

build-san: deps
	@bash scripts/build.sh $(BUILD_SAN) $(JOBS) "-DCMAKE_BUILD_TYPE=RelWithDebInfo -DGF_SANITIZE=ON -DGF_WERROR=$(GF_WERROR) $(CMAKE_ARGS)"

# The MPI build (GF_MPI=ON): mpirun -np N ./build-mpi/granflow run ... splits
# the spatial fixed step between ranks (docs/performance.md).
build-mpi: deps
	@bash scripts/build.sh $(BUILD_MPI) $(JOBS) "-DCMAKE_BUILD_TYPE=Release -DGF_MPI=ON -DGF_WERROR=$(GF_WERROR) $(CMAKE_ARGS)" granflow_cli

# The libFuzzer harnesses of tests/fuzz (clang, ASan + UBSan; docs/reliability.md).
build-fuzz: deps
	@bash scripts/build.sh $(BUILD_FUZZ) $(JOBS) "-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DGF_FUZZ=ON -DGF_WERROR=$(GF_WERROR)"

# The papers' silo: pack, drain for $(RUN_TAU) tau on every core (the
# parallel spatial fixed step; RUN_ENGINE= for the serial event-driven one),
# write snapshots + summary into $(RUN_DIR), then measure it the papers' way
# ($(RUN_DIR)/analysis: CSV files, plots, summary.json) and draw it
# ($(RUN_DIR)/render: slices coloured by layer and by packing fraction, a
# contact sheet), and put it all on one page ($(RUN_DIR)/report.html).
# `make run RUN_TAU=60` for the paper's Fig. 3.
run: build-cli
	@echo "run: [1/4] draining the papers' silo for $(RUN_TAU) tau into $(RUN_DIR)"
	@./$(BUILD)/granflow run --force $(RUN_ENGINE) --set run.duration=$(RUN_TAU) -o $(RUN_DIR)
	@echo "run: [2/4] measuring it the papers' way ($(RUN_DIR)/analysis)"
	@./$(BUILD)/granflow analyze $(RUN_DIR)
	@echo "run: [3/4] drawing it ($(RUN_DIR)/render)"
	@./$(BUILD)/granflow render -q $(RUN_DIR)
	@echo "run: [4/4] one page of it ($(RUN_DIR)/report.html)"
	@./$(BUILD)/granflow report -q $(RUN_DIR)
	@echo "run directory: $(RUN_DIR) (snapshots/, exits.csv, summary.json, analysis/, render/, report.html)"

# The whole suite: optimised build, then again under ASan + UBSan, then a
# short pass of every fuzzer (replaying every saved input first).
test: test-fast test-san test-fuzz test-mpi

# CTest runs $(JOBS) tests at once, and many of them start OpenMP threads on
# every core: threads that wait passively leave their core to the other
# tests (libgomp's default spins first; up to 25% of a threaded test's CPU
# on a busy 2-core machine). Results do not depend on it.
TEST_ENV = OMP_WAIT_POLICY=passive

test-fast: build
	cd $(BUILD) && $(TEST_ENV) ctest --output-on-failure -j $(JOBS)

test-san: build-san
	cd $(BUILD_SAN) && $(TEST_ENV) ctest --output-on-failure -j $(JOBS) -LE nosan

# The MPI tests only (label mpi): 1, 2 and 4 ranks give the single process's run directory.
test-mpi: build-mpi
	cd $(BUILD_MPI) && ctest --output-on-failure -L '^mpi$$'

test-fuzz: build-fuzz
	FUZZ_SECONDS=$(FUZZ_TEST_SECONDS) bash scripts/fuzz.sh $(BUILD_FUZZ)

# Every fuzzer for FUZZ_SECONDS (default 60) each; crashes are saved as
# tests/fuzz/<target>/regressions/ inputs (commit them: make test replays them).
fuzz: build-fuzz
	FUZZ_SECONDS=$(FUZZ_SECONDS) bash scripts/fuzz.sh $(BUILD_FUZZ)

bench: build-cli
	./$(BUILD)/granflow bench

# LAMMPS on the same silo and cores, for the side-by-side wall time per tau
# (docs/performance.md); about 4 minutes. Not part of `make bench`.
bench-dem: build-cli
	bash scripts/bench-dem.sh ./$(BUILD)/granflow $(BUILD)/bench-dem

# Every variant of the 2009 paper (examples/fig*.ini), shortened to fit a
# 2-core machine in well under an hour (two runs at a time), measured, drawn
# and compared with the paper in reproduce/REPORT.md; runs in reproduce/runs.
# Resumable; `REPRO_SCALE=0.05 make reproduce` is a smoke test of a couple of
# minutes (see scripts/reproduce-2009.sh). Not part of `make test`.
reproduce: build-cli
	GRANFLOW=./$(BUILD)/granflow bash scripts/reproduce-2009.sh

clean:
	rm -rf $(BUILD) $(BUILD_SAN) $(BUILD_FUZZ)
