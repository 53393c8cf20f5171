# granflow — the two commands: `make run` and `make test`.
# Everything else goes through CMake; this file only sequences it.
BUILD      ?= build
BUILD_SAN  ?= build-san
GF_WERROR  ?= OFF
RUN_DIR    ?= runs/silo
RUN_TAU    ?= 40
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

.PHONY: all deps build build-san run test test-fast test-san bench clean

all: build

deps:
	@bash scripts/deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DGF_WERROR=$(GF_WERROR) $(CMAKE_ARGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

build-san: deps
	@cmake -S . -B $(BUILD_SAN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGF_SANITIZE=ON -DGF_WERROR=$(GF_WERROR) $(CMAKE_ARGS) >/dev/null
	@cmake --build $(BUILD_SAN) -j $(JOBS)

# The papers' silo: pack, drain for $(RUN_TAU) tau (about 3 minutes), write
# snapshots + summary into $(RUN_DIR), then draw the central slice at the
# start, half-way and at the end. `make run RUN_TAU=60` for the paper's Fig. 3.
run: build
	./$(BUILD)/granflow run --force --set run.duration=$(RUN_TAU) -o $(RUN_DIR)
	@snaps=$$(ls $(RUN_DIR)/snapshots/snap_*.dump); n=$$(echo "$$snaps" | wc -l); \
	  scripts/slice.sh $(RUN_DIR)/slices.png $$(echo "$$snaps" | sed -n "1p;$$(( (n + 1) / 2 ))p;$${n}p")
	@echo "run directory: $(RUN_DIR) (snapshots/, exits.csv, summary.json, slices.png)"

# The whole suite: optimised build, then again under ASan + UBSan.
test: test-fast test-san

test-fast: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-san: build-san
	cd $(BUILD_SAN) && ctest --output-on-failure -j $(JOBS) -LE nosan

bench: build
	./$(BUILD)/granflow bench

clean:
	rm -rf $(BUILD) $(BUILD_SAN)
