# gomboc — thin top-level Makefile. Flags live in one place (below); `pkg-config` finds the
# libraries. The public targets first install missing Debian packages (scripts/install-deps.sh),
# then re-enter make so that pkg-config runs only once the packages are there.

PYTHON    := /usr/bin/python3
# the compilations, and the independent scene runs and animations, of make run and make verify: so many at a time (the
# machine's processors)
JOBS      ?= $(shell nproc 2>/dev/null || echo 1)
# The Python package's place under PREFIX: lib/python3.X/dist-packages, where Debian's python3 looks under
# /usr/local (another PREFIX: PYTHONPATH names it, README).
PYDIR      = $(PREFIX)/lib/$(shell $(PYTHON) -c 'import sys; print("python3.%d" % sys.version_info.minor)')/dist-packages
BUILD     := build
OUT       := reports/out
PKGS      := gsl cunit inih libcjson qhull_r libsodium libmatheval
CC        ?= cc
# Loops aligned to 64 bytes: make bench's reference, the paper's plain loop over the grid, is a 63-byte
# loop that ran 37 % slower (18.5 against 13.7 us a query) when a change elsewhere in the library moved it
# across a 64-byte line; aligned, its speed no longer depends on the link layout. No result changes.
# -O3 rather than -O2: the certified continuous run 8 % faster (the whole process, paired), every shipped scene's
# fingerprint the same bits (-ffp-contract=off below keeps every product and sum as written at either level).
CFLAGS    ?= -O3 -g -falign-loops=64
# Warnings are errors in `make verify` (and so in CI), not in a user's own build: WERROR=-Werror turns them on.
WERROR    ?=
WARN      := -std=c11 -D_GNU_SOURCE -ffp-contract=off -Wall -Wextra $(WERROR)
# OpenMP for the harness's independent long computations (s6_chaos) where the compiler has it; the
# library's scan runner uses POSIX threads (src/gb_scan_run.c says why).
OPENMP    := $(shell echo 'int main(void){return 0;}' | $(CC) -fopenmp -x c - -o /dev/null 2>/dev/null && echo -fopenmp)
# Siconos's numerics (the time-stepping strategy's contact problems) ships no pkg-config file: its headers' folders.
# The library is opened when a run first needs it (gb_contact_problem.c: dlopen), by the soname found here, so that
# the processes that never time-step do not load it and the twenty libraries under it.
SICONOS_CFLAGS := -I/usr/include/siconos/numerics -I/usr/include/siconos
SICONOS_SONAME := $(shell objdump -p $$($(CC) -print-file-name=libsiconos_numerics.so) 2>/dev/null | awk '/SONAME/ {print $$2}')
SICONOS_LIBS   := -ldl
SICONOS_CFLAGS += $(if $(SICONOS_SONAME),-DGB_SICONOS_NUMERICS='"$(SICONOS_SONAME)"')
# Arb (Debian libflint-arb-dev: the proofs' ball arithmetic, src/gb_proof.c) and FLINT under it: no pkg-config file
# either; its headers sit in /usr/include, FLINT's in /usr/include/flint; GMP under FLINT for its exact rationals
# (gb_proof_cover.c: a map read in a frame).
ARB_LIBS       := -lflint-arb -lflint -lgmp
ALL_CFLAGS = $(WARN) $(CPPFLAGS) $(CFLAGS) $(shell pkg-config --cflags $(PKGS)) $(SICONOS_CFLAGS) -Isrc
CORE_LIBS  = $(shell pkg-config --libs gsl libcjson inih qhull_r libsodium libmatheval) $(SICONOS_LIBS) $(ARB_LIBS) -lpthread -lm
TEST_LIBS  = $(shell pkg-config --libs cunit)

CORE_SRC  := $(sort $(wildcard src/gb_*.c))
CORE_OBJ  := $(CORE_SRC:src/%.c=$(BUILD)/obj/%.o)
CLI_SRC   := $(sort $(wildcard src/gomboc*.c))
CLI_OBJ   := $(CLI_SRC:src/%.c=$(BUILD)/obj/%.o)
# gomboc prove runs gomboc-prove (src/gomboc_prove_exec.c says why): gomboc is linked without the proofs and, with
# --as-needed, without Arb, FLINT, NTL and C++'s library; gomboc-prove is the whole command.
# Every gomboc_prove*.c but the exec shim belongs to gomboc-prove alone, by wildcard: a statement's new file cannot end
# up in gomboc and link Arb into it.
PROVE_OBJ := $(patsubst src/%.c,$(BUILD)/obj/%.o,$(filter-out src/gomboc_prove_exec.c,$(wildcard src/gomboc_prove*.c)))
PROVE_BIN  = $(BUILD)/gomboc-prove
LIB       := $(BUILD)/libgomboc.a
# The shared library beside the static one: soname libgomboc.so.$(SOMAJOR), built from position-independent
# objects of their own (build/pic), only for install and the examples.
# The release: one semantic version (0.x.y), in the file VERSION alone; `gomboc --version`, gomboc.pc and the
# shared library's file name read it (CHANGELOG.md says what each release holds).
VERSION   := $(shell cat VERSION)
SOMAJOR   := $(word 1,$(subst ., ,$(VERSION)))
SOMINOR   := $(word 2,$(subst ., ,$(VERSION)))
SONAME    := libgomboc.so.$(SOMAJOR)
SOLIB     := $(BUILD)/$(SONAME).$(SOMINOR)
PIC_OBJ   := $(CORE_SRC:src/%.c=$(BUILD)/pic/%.o)
BIN       := $(BUILD)/gomboc
VERIFY_SRC := $(sort $(wildcard verify/*.c))
VERIFY_OBJ := $(VERIFY_SRC:verify/%.c=$(BUILD)/obj/verify_%.o)
VERIFY_BIN := $(BUILD)/verify-gomboc
BENCH_BIN  := $(BUILD)/bench-gomboc
BENCH_SRC  := $(sort $(wildcard verify/bench/bench*.c))
# make bench's baseline: the best plain loop (verify/bench/plain.c) with the bench and the library around
# it, built apart with the best flags of this compiler
NATIVE_FLAGS := -O3 -march=native -falign-loops=64
NATIVE_OBJ := $(CORE_SRC:src/%.c=$(BUILD)/native/%.o)
BENCH_NATIVE := $(BUILD)/bench-gomboc-native
# MPI: gomboc-mpi is the command with `gomboc scan` built by mpicc, where mpicc is (make mpi installs
# Debian's OpenMPI). Its checks launch it through MPIRUN (root needs OpenMPI's explicit consent).
MPICC     := $(shell command -v mpicc 2>/dev/null)
MPI_BIN   := $(BUILD)/gomboc-mpi
MPIRUN    := mpirun --oversubscribe$(if $(filter 0,$(shell id -u)), --allow-run-as-root)
MPI_ENV    = $(if $(MPICC),GOMBOC_MPI_BIN=$(MPI_BIN) GOMBOC_MPIRUN="$(MPIRUN)")

.PHONY: all deps run verify verify-full bench references report install clean distclean example \
        build run-only verify-only verify-scenes references-only bench-only fuzz fuzz-only sanitize sanitize-only \
        valgrind valgrind-only install-only example-only scans scans-only study study-only prove prove-only mpi mpi-only \
        check help uninstall

all: deps
	@$(MAKE) --no-print-directory build

deps:
	@sh scripts/install-deps.sh

build: $(BIN) $(VERIFY_BIN)

# --- the main job on its default scene: the shape study of both Table 1 bodies (β = 0.12)
run: deps
	@$(MAKE) --no-print-directory -j$(JOBS) $(BIN)
	@$(MAKE) --no-print-directory run-only

# The Table 1 scenes `make run` integrates, and the ones `make verify` adds (both readings of A1, A2,
# and the harmonic benchmark, eq 94).
RUN_SCENES    := table1-gomboc-I table1-gomboc-II
# Bodies of one's own (cases/bodies/): a mesh's polyhedron rocking, tumbling and falling flat; `make run` runs
# them too, and the shape study covers the body of every scene it runs.
BODY_SCENES   := bodies/housner-block bodies/die-drop bodies/coin bodies/housner-block-compliant bodies/coin-friction
# Each Table 1 body under the unilateral law, seen in motion: `make run` runs these and draws a short
# animation of each (reports/animate.py; an MP4 through ffmpeg where it is installed, else a GIF).
ANIMATED      := table1-gomboc-I-unilateral table1-gomboc-II-unilateral
# and a mesh body's (its hull's faces, from gomboc shape --faces): the die landing on a vertex and tumbling to a face
ANIMATED_BODIES := die-drop
VERIFY_SCENES := $(RUN_SCENES) table1-gomboc-I-g-units table1-gomboc-II-g-units harmonic-gomboc-I harmonic-gomboc-II \
                 table1-gomboc-I-rolling table1-gomboc-II-rolling table1-gomboc-I-unilateral table1-gomboc-II-unilateral \
                 table1-gomboc-I-grid-unilateral table1-gomboc-II-grid-unilateral \
                 table1-gomboc-I-g-units-unilateral table1-gomboc-II-g-units-unilateral \
                 table1-gomboc-I-g-units-bouncing table1-gomboc-II-g-units-bouncing

run-only: $(BIN)
	@mkdir -p $(OUT)
	printf '%s\n' $(RUN_SCENES) $(BODY_SCENES) | xargs -P $(JOBS) -I@ sh -c 'n=$$(basename @); \
	  map=$$(grep -q "^mesh *=" cases/@.ini && echo "--faces $(OUT)/faces-$$n.csv" || echo "--radial-map $(OUT)/radial-map-$$n.csv"); \
	  $(BIN) shape --scene cases/@.ini --json $$map > $(OUT)/shape-$$n.json.tmp && mv $(OUT)/shape-$$n.json.tmp $(OUT)/shape-$$n.json' \
	  || exit 1
	$(PYTHON) reports/shape_report.py $(OUT) $(notdir $(RUN_SCENES) $(BODY_SCENES))
	printf '%s\n' $(RUN_SCENES) $(BODY_SCENES) $(ANIMATED) | xargs -P $(JOBS) -I@ $(BIN) run cases/@.ini --out $(OUT) || exit 1
	printf '%s\n' $(ANIMATED) | xargs -P $(JOBS) -I@ sh -c '$(PYTHON) reports/animate.py $(OUT) @ --seconds 4 --fps 15 \
	  --surface $(OUT)/radial-map-$$(echo @ | sed "s/-unilateral$$//").csv' || exit 1
	for s in $(ANIMATED_BODIES); do $(PYTHON) reports/animate.py $(OUT) $$s --seconds 1 --fps 15 || exit 1; done
	$(PYTHON) reports/run_report.py $(OUT) $(notdir $(RUN_SCENES) $(BODY_SCENES)) $(ANIMATED) --page runs.md
	@echo "run: reports written to $(OUT)/shape.md and $(OUT)/runs.md (with the animations of $(ANIMATED) $(ANIMATED_BODIES))"

# --- every check, then the reproducibility report
verify: deps
	@$(MAKE) --no-print-directory -j$(JOBS) $(BIN) $(VERIFY_BIN) $(SOLIB) $(if $(MPICC),$(MPI_BIN)) WERROR=-Werror
	@$(MAKE) --no-print-directory verify-only WERROR=-Werror

# Figure 2 of the paper: the height landscape for one documented vertical (see reports/contact_section.py).
FIG2_ZB := 0.6,0.6,-0.5
FIG2     = $(BIN) contact --beta 0.12 --zb $(FIG2_ZB) --json

# The checks read none of the scenes' outputs, so they start first and run beside the scenes; with two cores or more
# (JOBS) the harness runs half its suites in a second process (verify/main.c, --jobs). Their output goes to a log that
# is shown after the scenes' own output, as it grows, so CUnit's run summary stays the last thing printed before the
# report line.
# The checks' temporary directories live in one directory of the run's own (their TMPDIR), removed at the end and on
# an interruption whatever a check left.
verify-only: $(BIN) $(VERIFY_BIN) $(SOLIB) $(if $(MPICC),$(MPI_BIN))
	@mkdir -p $(OUT)
	@scratch=$$(mktemp -d "$${TMPDIR:-/tmp}/gomboc-checks-XXXXXX") || exit 1; checks=; \
	trap 'rm -rf "$$scratch"' EXIT; trap '[ -z "$$checks" ] || kill $$checks 2>/dev/null; rm -rf "$$scratch"; exit 130' INT TERM; \
	TMPDIR=$$scratch GOMBOC_BIN=$(BIN) GOMBOC_LIB=$(SOLIB) $(MPI_ENV) $(VERIFY_BIN) --results $(OUT)/checks.json --data $(OUT) \
	  --jobs $(JOBS) $(VERIFY_FLAGS) > $(OUT)/checks.log 2>&1 & checks=$$!; \
	$(MAKE) --no-print-directory verify-scenes; scenes=$$?; \
	echo "verify: the checks ($(VERIFY_BIN), started beside the scenes; their log $(OUT)/checks.log):"; \
	tail -n +1 --pid=$$checks -f $(OUT)/checks.log; \
	wait $$checks; status=$$?; \
	[ $$scenes -eq 0 ] || { echo "verify: the scenes above failed"; status=1; }; \
	$(PYTHON) reports/make_report.py $(OUT) "$(CC)" "$(WARN) $(CFLAGS)" || status=1; \
	echo "verify: report written to $(OUT)/verification.md"; \
	exit $$status

# What `make verify` runs beside its checks: `make run`'s work, the example, the scenes it adds and Figure 2.
verify-scenes: $(BIN) $(SOLIB)
	@$(MAKE) --no-print-directory run-only
	@$(MAKE) --no-print-directory example-only
	@mkdir -p $(OUT)
	printf '%s\n' $(filter-out $(RUN_SCENES) $(ANIMATED),$(VERIFY_SCENES)) | xargs -P $(JOBS) -I@ $(BIN) run cases/@.ini --out $(OUT) \
	  || exit 1
	$(PYTHON) reports/run_report.py $(OUT) $(VERIFY_SCENES) $(notdir $(BODY_SCENES)) --page runs.md
	for m in I II; do \
	  $(FIG2) --morphology $$m --method continuous --grid 180x360 --landscape $(OUT)/fig2-landscape-$$m.csv \
	    --zoom $(OUT)/fig2-zoom-$$m.csv --zoom-halfwidth 0.4 > $(OUT)/fig2-contact-$$m.json.tmp && \
	  mv $(OUT)/fig2-contact-$$m.json.tmp $(OUT)/fig2-contact-$$m.json && \
	  $(FIG2) --morphology $$m --method continuous --zoom $(OUT)/fig2-zoom-fine-$$m.csv --zoom-halfwidth 0.08 \
	    > /dev/null && \
	  $(FIG2) --morphology $$m --method grid > $(OUT)/fig2-grid-$$m.json.tmp && \
	  mv $(OUT)/fig2-grid-$$m.json.tmp $(OUT)/fig2-grid-$$m.json || exit 1; \
	done

# --- speed, printed as ratios measured in one run (never asserted in tests)
bench: deps
	@sh scripts/install-deps.sh siconos || echo "bench: Siconos could not be installed: its comparison is skipped"
	@$(MAKE) --no-print-directory bench-only

# gomboc against Siconos (verify/bench/against_siconos.py) where Siconos is installed: the work-precision ratio
bench-only: $(BENCH_BIN) $(BENCH_NATIVE) $(BIN)
	@mkdir -p $(OUT)
	status=0; PYTHON=$(PYTHON) $(BENCH_BIN) $(OUT)/bench.json $(BENCH_NATIVE) $(BIN) || status=$$?; \
	$(PYTHON) verify/bench/rest_faces.py $(BIN) $(OUT)/bench-rest-faces.json || status=1; \
	$(PYTHON) verify/bench/compliant.py $(BIN) $(OUT)/bench-compliant.json || status=1; \
	if $(PYTHON) -c "import siconos.kernel" 2>/dev/null; then \
	  $(PYTHON) verify/bench/against_siconos.py $(BIN) $(OUT)/bench-siconos.json || status=1; \
	else echo "bench: gomboc against Siconos skipped: Siconos absent (sh scripts/install-deps.sh siconos)"; fi; \
	sh scripts/gate-stamp.sh $(GATES) bench $$status "speed ratios measured side by side in one run"; exit $$status

# Everything `make verify` does, plus the long studies (harness --full): continuous rolling over 10000
# periods, post-transient exponents of the unforced bodies; then the ensembles of `make study`.
verify-full: deps
	@sh scripts/install-deps.sh fuzz
	@$(MAKE) --no-print-directory fuzz-only FUZZ_SECONDS=30
	@status=0; $(MAKE) --no-print-directory verify-only VERIFY_FLAGS=--full WERROR=-Werror || status=$$?; \
	$(MAKE) --no-print-directory study-only || status=1; \
	sh scripts/gate-stamp.sh $(GATES) verify-full $$status "every check, the long studies and the ensembles"; \
	$(PYTHON) reports/make_report.py $(OUT) "$(CC)" "$(WARN) $(CFLAGS)" || status=1; exit $$status

# --- the maps of Figs 10-13 (cases/scans: both bodies, both planes, the paper's and the rolling model under
# the held law; the rolling model under the unilateral law in m/s2 and in units of g with flight, and the grid
# polyhedron for Figs 10 and 12), 25 x 25 points of 100 periods each, lambda included, and a 5 x 5 preview of Fig 10
# in units of g stepped in time on a plane of friction 0.5; then their stability
# maps (cases/scans/stability: 200 periods a point, and a refined sub-window; no lambda); resumable (an interrupted `make scans` goes
# on from each scan's journal). The report shows the last maps made, with their date and commit.
SCANS := $(sort $(wildcard cases/scans/*.ini)) $(sort $(wildcard cases/scans/stability/*.ini))

scans: deps
	@$(MAKE) --no-print-directory scans-only

# $(call scan_all,FILES,GATE,WHAT): every scan file into $(OUT)/GATE (resuming any journal), the gate
# stamped, the report regenerated.
scan_all = mkdir -p $(OUT)/$(2); status=0; \
	for s in $(1); do $(BIN) scan $$s --out $(OUT)/$(2) --resume || { status=$$?; break; }; done; \
	sh scripts/gate-stamp.sh $(GATES) $(2) $$status "the $(words $(1)) $(3)"; \
	$(PYTHON) reports/make_report.py $(OUT) "$(CC)" "$(WARN) $(CFLAGS)" || status=1; exit $$status

scans-only: $(BIN)
	$(call scan_all,$(SCANS),scans,maps of cases/scans)

# --- the ensembles of section 8.2 (cases/studies): 32 random initial attitudes per body, 3000 periods
# each (16 x 1000 in units of g and on planes of finite friction), lambda over the record and its halves;
# resumable like the scans.
STUDIES := $(sort $(wildcard cases/studies/*.ini))

study: deps
	@$(MAKE) --no-print-directory study-only

study-only: $(BIN)
	$(call scan_all,$(STUDIES),study,ensembles of cases/studies)

# --- the statements proved on Arb's balls (docs/proofs.md): gomboc prove, its JSON in reports/out/proofs.json (make
# verify runs it too, in its harness, and draws the report's section "Proved" from it); then Gömböc II's horseshoe
# (gomboc prove --horseshoe, minutes: make prove alone), its JSON in reports/out/proof-horseshoe.json; exit 1 when one
# is not proved.
prove: deps
	@$(MAKE) --no-print-directory prove-only

prove-only: $(BIN)
	@mkdir -p $(OUT)
	$(BIN) prove --large-trellis --json > $(OUT)/proofs.json.tmp && mv $(OUT)/proofs.json.tmp $(OUT)/proofs.json
	@$(PYTHON) -c 'import json, sys; [print(s["statement"] + ": " + s["result"] + " " + s["summary"]) \
	  for s in json.load(open(sys.argv[1]))["statements"]]' $(OUT)/proofs.json
	$(BIN) prove --horseshoe --json > $(OUT)/proof-horseshoe.json.tmp && \
	  mv $(OUT)/proof-horseshoe.json.tmp $(OUT)/proof-horseshoe.json
	@$(PYTHON) -c 'import json, sys; [print(s["statement"] + ": " + s["result"] + " " + s["summary"]) \
	  for s in json.load(open(sys.argv[1]))["statements"]]' $(OUT)/proof-horseshoe.json

# --- scans on MPI ranks: OpenMPI installed, gomboc-mpi built, and its checks (1, 2 and 3 ranks, a kill -9
# of every rank and --resume: the same bytes as one thread). make verify runs them too where mpicc is.
mpi: deps
	@sh scripts/install-deps.sh mpi
	@$(MAKE) --no-print-directory mpi-only

mpi-only: $(BIN) $(VERIFY_BIN)
	@$(MAKE) --no-print-directory $(MPI_BIN)
	@mkdir -p $(BUILD)/mpi
	status=0; GOMBOC_BIN=$(BIN) GOMBOC_MPI_BIN=$(MPI_BIN) GOMBOC_MPIRUN="$(MPIRUN)" $(VERIFY_BIN) --only "MPI ranks" \
	  --results $(BUILD)/mpi/checks.json --data $(BUILD)/mpi > $(BUILD)/mpi/verify.log 2>&1 || status=1; \
	summary=$$(grep -A3 'Run Summary' $(BUILD)/mpi/verify.log | tail -n 1 | tr -s ' '); \
	tail -n 6 $(BUILD)/mpi/verify.log; \
	sh scripts/gate-stamp.sh $(GATES) mpi $$status "gomboc-mpi on 1, 2 and 3 ranks, kill -9 and --resume ($$(mpirun --version | head -n 1));$$summary"; \
	exit $$status

# --- quality gates on bad input and memory; each writes $(OUT)/gates/GATE.json for the report ----------
GATES := $(OUT)/gates

# The scene reader, the option parser, and the atlas file, hull file, scan file and scan journal readers under
# libFuzzer (clang, with ASan and UBSan), FUZZ_SECONDS each, seeded from cases/, cases/scans and
# verify/fuzz/options.seeds, with dictionaries of the keys and options.
# A crash or a broken invariant stops it and leaves build-fuzz/crash-*; add such an input to
# verify/bad_input.c's table.
FUZZ_SECONDS ?= 300
FUZZ_DIR     := build-fuzz
FUZZ_CFLAGS  := -std=c11 -D_GNU_SOURCE -ffp-contract=off -Wall -Wextra -Werror -g -O1 \
                -fsanitize=address,undefined -fno-sanitize-recover=undefined
fuzz: deps
	@sh scripts/install-deps.sh fuzz
	@$(MAKE) --no-print-directory fuzz-only

FUZZ_TARGETS := case options atlas hull scan journal mesh expression
fuzz-only: $(FUZZ_TARGETS:%=$(FUZZ_DIR)/fuzz-%)
	@mkdir -p $(FUZZ_TARGETS:%=$(FUZZ_DIR)/corpus-%)
	@n=0; while IFS= read -r line; do n=$$((n+1)); printf '%s' "$$line" | tr ' ' '\000' > $(FUZZ_DIR)/corpus-options/seed-$$n; \
	  done < verify/fuzz/options.seeds
	@cp verify/fuzz/hull.seed $(FUZZ_DIR)/corpus-hull/seed
	@cp verify/fuzz/mesh/* $(FUZZ_DIR)/corpus-mesh/
	@cp verify/fuzz/expression/* $(FUZZ_DIR)/corpus-expression/
	status=0; export GOMBOC_KEY=$(abspath $(FUZZ_DIR))/key LSAN_OPTIONS=suppressions=$(abspath verify/lsan.supp); \
	$(FUZZ_DIR)/fuzz-case -max_total_time=$(FUZZ_SECONDS) -dict=verify/fuzz/case.dict -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-case- $(FUZZ_DIR)/corpus-case cases > $(FUZZ_DIR)/fuzz-case.log 2>&1 || status=1; \
	$(FUZZ_DIR)/fuzz-options -max_total_time=$(FUZZ_SECONDS) -dict=verify/fuzz/options.dict -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-options- $(FUZZ_DIR)/corpus-options > $(FUZZ_DIR)/fuzz-options.log 2>&1 || status=1; \
	$(FUZZ_DIR)/fuzz-atlas -max_total_time=$(FUZZ_SECONDS) -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-atlas- $(FUZZ_DIR)/corpus-atlas > $(FUZZ_DIR)/fuzz-atlas.log 2>&1 || status=1; \
	$(FUZZ_DIR)/fuzz-hull -max_total_time=$(FUZZ_SECONDS) -use_value_profile=1 -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-hull- $(FUZZ_DIR)/corpus-hull > $(FUZZ_DIR)/fuzz-hull.log 2>&1 || status=1; \
	$(FUZZ_DIR)/fuzz-scan -max_total_time=$(FUZZ_SECONDS) -dict=verify/fuzz/scan.dict -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-scan- $(FUZZ_DIR)/corpus-scan cases/scans > $(FUZZ_DIR)/fuzz-scan.log 2>&1 || status=1; \
	$(FUZZ_DIR)/fuzz-journal -max_total_time=$(FUZZ_SECONDS) -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-journal- $(FUZZ_DIR)/corpus-journal > $(FUZZ_DIR)/fuzz-journal.log 2>&1 || status=1; \
	$(FUZZ_DIR)/fuzz-mesh -max_total_time=$(FUZZ_SECONDS) -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-mesh- $(FUZZ_DIR)/corpus-mesh > $(FUZZ_DIR)/fuzz-mesh.log 2>&1 || status=1; \
	$(FUZZ_DIR)/fuzz-expression -max_total_time=$(FUZZ_SECONDS) -close_fd_mask=3 \
	  -artifact_prefix=$(FUZZ_DIR)/crash-expression- $(FUZZ_DIR)/corpus-expression > $(FUZZ_DIR)/fuzz-expression.log 2>&1 || status=1; \
	runs="$$(grep -h '^Done' $(FUZZ_TARGETS:%=$(FUZZ_DIR)/fuzz-%.log) | tr '\n' ';')"; \
	tail -n 3 $(FUZZ_TARGETS:%=$(FUZZ_DIR)/fuzz-%.log); \
	sh scripts/gate-stamp.sh $(GATES) fuzz $$status "$(FUZZ_SECONDS) s per target (case reader; option parser; atlas file reader; hull file reader; scan file reader; scan journal reader; mesh reader; body expressions): $$runs"; \
	echo "fuzz: $$( [ $$status -eq 0 ] && echo 'no crash' || echo 'FAILED: see build-fuzz/*.log and build-fuzz/crash-*')"; \
	exit $$status

$(FUZZ_DIR)/fuzz-case $(FUZZ_DIR)/fuzz-atlas $(FUZZ_DIR)/fuzz-hull $(FUZZ_DIR)/fuzz-scan $(FUZZ_DIR)/fuzz-journal $(FUZZ_DIR)/fuzz-mesh $(FUZZ_DIR)/fuzz-expression: $(FUZZ_DIR)/fuzz-%: verify/fuzz/fuzz_%.c $(CORE_SRC) $(wildcard src/*.h verify/fuzz/*.h)
	@mkdir -p $(FUZZ_DIR)
	clang $(FUZZ_CFLAGS) -fsanitize=fuzzer $(shell pkg-config --cflags $(PKGS)) $(SICONOS_CFLAGS) -Isrc -o $@ $< $(CORE_SRC) $(CORE_LIBS)

$(FUZZ_DIR)/fuzz-options: verify/fuzz/fuzz_options.c $(CORE_SRC) $(CLI_SRC) $(wildcard src/*.h)
	@mkdir -p $(FUZZ_DIR)
	clang $(FUZZ_CFLAGS) -fsanitize=fuzzer -DGOMBOC_NO_MAIN $(shell pkg-config --cflags $(PKGS)) $(SICONOS_CFLAGS) -Isrc -o $@ $< \
	  $(CORE_SRC) $(CLI_SRC) $(CORE_LIBS)

# Every check of the harness under AddressSanitizer and UndefinedBehaviorSanitizer (a separate build in
# build-san; the command the checks run is the sanitized one too). Any report fails the gate.
SAN_FLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined
sanitize: deps
	@$(MAKE) --no-print-directory sanitize-only

sanitize-only:
	@$(MAKE) --no-print-directory BUILD=build-san CFLAGS="$(SAN_FLAGS)" build-san/gomboc build-san/verify-gomboc
	@mkdir -p build-san/data
	status=0; \
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 LSAN_OPTIONS=suppressions=$(abspath verify/lsan.supp) \
	  GOMBOC_BIN=build-san/gomboc build-san/verify-gomboc --results build-san/checks.json --data build-san/data \
	  > build-san/verify.log 2>&1 || status=1; \
	reports=$$(grep -c -E 'ERROR: (Address|Leak)Sanitizer|runtime error:' build-san/verify.log || true); \
	summary=$$(grep -A3 'Run Summary' build-san/verify.log | tail -n 1 | tr -s ' '); \
	tail -n 6 build-san/verify.log; \
	sh scripts/gate-stamp.sh $(GATES) sanitize $$status "ASan+UBSan, every check: $$reports sanitizer reports;$$summary"; \
	echo "sanitize: $$reports sanitizer reports (log: build-san/verify.log)"; \
	exit $$status

# One short scene of each model (verify/valgrind/*.ini) and the shape and contact commands under
# valgrind's memcheck: any error or definite/indirect leak fails the gate.
VALGRIND := valgrind --quiet --error-exitcode=3 --leak-check=full --errors-for-leak-kinds=definite,indirect \
            --show-leak-kinds=definite,indirect
valgrind: deps
	@sh scripts/install-deps.sh valgrind
	@$(MAKE) --no-print-directory valgrind-only

valgrind-only: $(BIN) $(VERIFY_BIN)
	@mkdir -p $(BUILD)/valgrind
	status=0; n=0; export GOMBOC_KEY=$(abspath $(BUILD))/valgrind/key; \
	for s in verify/valgrind/*.ini; do n=$$((n+1)); \
	  $(VALGRIND) $(BIN) run $$s --out $(BUILD)/valgrind || { status=1; echo "valgrind: $$s FAILED"; }; done; \
	$(VALGRIND) $(BIN) shape --morphology II --beta 0.12 --json > /dev/null || { status=1; echo "valgrind: shape FAILED"; }; \
	$(VALGRIND) $(BIN) contact --morphology I --beta 0.12 --zb 0.6,0.6,-0.5 --method continuous --json \
	  --landscape $(BUILD)/valgrind/landscape.csv --zoom $(BUILD)/valgrind/zoom.csv > /dev/null || { status=1; echo "valgrind: contact FAILED"; }; \
	rm -f $(BUILD)/valgrind/atlas.bin; for k in 1 2; do \
	  $(VALGRIND) $(BIN) run verify/valgrind/rolling-atlas.ini --out $(BUILD)/valgrind --atlas $(BUILD)/valgrind/atlas.bin \
	    || { status=1; echo "valgrind: atlas file FAILED"; }; done; \
	rm -f $(BUILD)/valgrind/hull.bin; for k in 1 2; do \
	  $(VALGRIND) $(BIN) run verify/valgrind/paper-fast-grid.ini --out $(BUILD)/valgrind --hull $(BUILD)/valgrind/hull.bin \
	    || { status=1; echo "valgrind: hull file FAILED"; }; done; \
	$(VALGRIND) $(BIN) run verify/valgrind/missing.ini 2> /dev/null; [ $$? -eq 2 ] || { status=1; echo "valgrind: bad input FAILED"; }; \
	$(VALGRIND) $(BIN) check $(BUILD)/valgrind/paper-grid-summary.json > /dev/null || { status=1; echo "valgrind: check FAILED"; }; \
	rm -f $(BUILD)/valgrind/small-scan.*; \
	$(VALGRIND) $(BIN) scan verify/valgrind/scan/small.ini --out $(BUILD)/valgrind --threads 1 || { status=1; echo "valgrind: scan FAILED"; }; \
	rm -f $(BUILD)/valgrind/shared-atlas-scan.*; \
	$(VALGRIND) $(BIN) scan verify/valgrind/scan/shared-atlas.ini --out $(BUILD)/valgrind --threads 1 || { status=1; echo "valgrind: shared-atlas scan FAILED"; }; \
	printf '#!/bin/sh\nexec $(subst --error-exitcode=3,--error-exitcode=99,$(VALGRIND)) %s "$$@"\n' $(abspath $(BIN)) > $(BUILD)/valgrind/gomboc-memcheck; \
	chmod +x $(BUILD)/valgrind/gomboc-memcheck; \
	GOMBOC_BIN=$(BUILD)/valgrind/gomboc-memcheck $(VERIFY_BIN) --only "Bad input" --results $(BUILD)/valgrind/bad-input.json \
	  > $(BUILD)/valgrind/bad-input.log 2>&1 || { status=1; echo "valgrind: the bad-input suite under memcheck FAILED (exit 99 is an error): see $(BUILD)/valgrind/bad-input.log"; }; \
	grep -A3 'Run Summary' $(BUILD)/valgrind/bad-input.log | tail -n 2; \
	sh scripts/gate-stamp.sh $(GATES) valgrind $$status "memcheck: $$n scenes (verify/valgrind), an atlas file and a hull file written and loaded, shape, contact, a scan, a scan sharing an atlas, a set checked and a refused input; every row and check of the bad-input suite through memcheck"; \
	echo "valgrind: $$( [ $$status -eq 0 ] && echo 'no errors, no leaks' || echo FAILED)"; \
	exit $$status

references: deps
	@sh scripts/install-deps.sh siconos || echo "references: Siconos could not be installed: references/siconos/*.json are kept"
	@$(MAKE) --no-print-directory references-only

references-only: $(BIN)
	$(PYTHON) references/massprops.py > references/massprops.json.tmp && mv references/massprops.json.tmp references/massprops.json
	$(PYTHON) references/contact.py > references/contact.json.tmp && mv references/contact.json.tmp references/contact.json
	$(PYTHON) references/dynamics.py > references/dynamics.json.tmp && mv references/dynamics.json.tmp references/dynamics.json
	$(PYTHON) references/spectrum.py > references/spectrum.json.tmp && mv references/spectrum.json.tmp references/spectrum.json
	$(PYTHON) references/henon_crossings.py > references/henon_crossings.json.tmp && \
	  mv references/henon_crossings.json.tmp references/henon_crossings.json
	$(PYTHON) references/grid_model.py > references/grid_model.json.tmp && mv references/grid_model.json.tmp references/grid_model.json
	$(PYTHON) references/switching.py > references/switching.json.tmp && mv references/switching.json.tmp references/switching.json
	@if $(PYTHON) -c "import siconos.numerics" 2>/dev/null; then \
	  for r in impacts bouncing_ball polyhedron one_step; do \
	    echo "$(PYTHON) references/siconos/$$r.py > references/siconos/$$r.json"; \
	    GOMBOC=$(BIN) $(PYTHON) references/siconos/$$r.py > references/siconos/$$r.json.tmp && \
	    mv references/siconos/$$r.json.tmp references/siconos/$$r.json || exit 1; \
	  done; \
	else echo "references: Siconos absent (sh scripts/install-deps.sh siconos): references/siconos/*.json kept as committed"; fi

# The command, the static and shared libraries, the public headers (src/gomboc.h includes them all; the
# internal ones, *_internal.h, gb_interval.h, gb_arena.h, gb_vec.h, gb_hash.h, gb_clock.h, the readers behind gb_case
# and gb_scan, gb_ini.h (gb_parse.h is public: gomboc.h includes it), the caches' seals, gb_seal.h, and a body expression's tree, gb_expression.h, stay), a pkg-config file and the man page, under $(DESTDIR)$(PREFIX).
PREFIX  ?= /usr/local
PRIVATE_HEADERS := %_internal.h src/gb_interval.h src/gb_arena.h src/gb_vec.h src/gb_hash.h src/gb_clock.h src/gb_ini.h src/gb_seal.h src/gb_expression.h
PUBLIC_HEADERS = src/gomboc.h $(filter-out $(PRIVATE_HEADERS),$(wildcard src/gb_*.h))

# Only what it installs is built (not the harness). No public header includes a dependency's, so the
# dependencies are Libs.private: a shared link needs -lgomboc alone (its NEEDED entries bring the rest),
# `pkg-config --static` adds them for libgomboc.a, and no dependency's -I reaches a user's flags.
install: deps
	@$(MAKE) --no-print-directory install-only

SHARE_REPORTS := reports/common.py reports/plot_scan.py reports/run_report.py reports/animate.py
install-only: $(BIN) $(LIB) $(SOLIB)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include/gomboc \
	  $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/share/gomboc/reports
	install -m 644 cases/README.md $(DESTDIR)$(PREFIX)/share/gomboc/scene-keys.md
	install -m 644 docs/outputs.md $(DESTDIR)$(PREFIX)/share/gomboc/outputs.md
	install -m 644 CHANGELOG.md $(DESTDIR)$(PREFIX)/share/gomboc/CHANGELOG.md
	install -m 644 $(SHARE_REPORTS) $(DESTDIR)$(PREFIX)/share/gomboc/reports/
	install -m 755 $(BIN) $(DESTDIR)$(PREFIX)/bin/gomboc
	install -m 755 $(PROVE_BIN) $(DESTDIR)$(PREFIX)/bin/gomboc-prove
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/libgomboc.a
	install -m 755 $(SOLIB) $(DESTDIR)$(PREFIX)/lib/$(notdir $(SOLIB))
	ln -sf $(notdir $(SOLIB)) $(DESTDIR)$(PREFIX)/lib/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(PREFIX)/lib/libgomboc.so
	install -m 644 $(PUBLIC_HEADERS) $(DESTDIR)$(PREFIX)/include/gomboc/
	install -m 644 docs/gomboc.1 $(DESTDIR)$(PREFIX)/share/man/man1/gomboc.1
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' scripts/gomboc.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/gomboc.pc
	install -d $(DESTDIR)$(PYDIR)/gomboc
	install -m 644 python/gomboc/__init__.py python/gomboc/plot.py $(DESTDIR)$(PYDIR)/gomboc/

# The README's example and a C++ program, compiled against a staged install with pkg-config (the shared
# library) and run from another directory; then the staged install is removed by make uninstall, which
# must leave its prefix empty (make verify runs this).
STAGE := $(abspath $(BUILD))/stage
STAGED_PC = PKG_CONFIG_PATH=$(STAGE)/usr/local/lib/pkgconfig pkg-config --define-variable=prefix=$(STAGE)/usr/local
example: deps
	@$(MAKE) --no-print-directory example-only

example-only: $(BIN) $(LIB) $(SOLIB)
	@rm -rf $(STAGE)
	@$(MAKE) --no-print-directory install-only DESTDIR=$(STAGE) PREFIX=/usr/local > /dev/null
	$(CC) -std=c11 -Wall -Wextra -Werror examples/contact_and_scene.c -o $(BUILD)/example $$($(STAGED_PC) --cflags --libs gomboc)
	cd / && LD_LIBRARY_PATH=$(STAGE)/usr/local/lib $(abspath $(BUILD))/example
	$(CXX) -std=c++17 -Wall -Wextra -Werror examples/cxx_link.cpp -o $(BUILD)/example-cxx $$($(STAGED_PC) --cflags --libs gomboc)
	cd / && LD_LIBRARY_PATH=$(STAGE)/usr/local/lib $(abspath $(BUILD))/example-cxx
	@case "$$($(STAGED_PC) --cflags gomboc)" in *cjson*|*gsl*) echo "example: a dependency's flags leak into --cflags"; exit 1;; esac
	@for h in $(notdir $(PUBLIC_HEADERS)); do \
	  printf '#include <%s>\nint main(void) { return 0; }\n' $$h | \
	  $(CC) -std=c11 -Wall -Wextra -Werror -fsyntax-only -x c - $$($(STAGED_PC) --cflags gomboc) \
	  || { echo "example: the installed header $$h does not compile on its own"; exit 1; }; done
	$(CC) -std=c11 -Wall -Wextra -Werror examples/contact_and_scene.c -o $(BUILD)/example-static $$($(STAGED_PC) --cflags gomboc) \
	  $$($(STAGED_PC) --static --libs gomboc | sed 's|-lgomboc|-l:libgomboc.a|')
	cd / && $(abspath $(BUILD))/example-static > /dev/null
	@! readelf -d $(BUILD)/example-static | grep -q 'NEEDED.*libgomboc' || { echo "example: the static link took the shared library"; exit 1; }
	@readelf -d $(BUILD)/example | grep -q 'NEEDED.*\[$(SONAME)\]' && readelf -d $(SOLIB) | grep -q 'SONAME.*\[$(SONAME)\]' \
	  || { echo "example: not linked against $(SONAME)"; exit 1; }
	@! readelf -d $(BIN) | grep -qE 'NEEDED.*(flint|arb)' \
	  || { echo "example: $(BIN) needs Arb or FLINT: a gomboc_prove*.c object reached it (PROVE_OBJ)"; exit 1; }
	@$(PYTHON) scripts/check_exports.py $(SOLIB) $(PUBLIC_HEADERS) --callers $(CLI_SRC) $(VERIFY_SRC) \
	  $(wildcard verify/fuzz/*.c verify/bench/*.c examples/*.c examples/*.cpp python/gomboc/*.py examples/*.py)
	$(CC) $(LDFLAGS) -o $(BUILD)/gomboc-shared $(CLI_OBJ) $$($(STAGED_PC) --libs gomboc) $(shell pkg-config --libs libcjson) -lm
	@readelf -d $(BUILD)/gomboc-shared | grep -q 'NEEDED.*\[$(SONAME)\]' || { echo "example: gomboc-shared not linked against $(SONAME)"; exit 1; }
	cd / && LD_LIBRARY_PATH=$(STAGE)/usr/local/lib $(abspath $(BUILD))/gomboc-shared contact --morphology I --beta 0.12 --method continuous --zb 0,0,-1 --json > /dev/null
	@test "$$($(STAGED_PC) --modversion gomboc)" = "$(VERSION)" && $(STAGED_PC) --atleast-version=0.1 gomboc && \
	  test "$$($(STAGE)/usr/local/bin/gomboc --version)" = "gomboc $(VERSION)" \
	  || { echo "example: gomboc.pc's Version and gomboc --version are not VERSION ($(VERSION))"; exit 1; }
	@test -z "$$(groff -man -ww -z $(STAGE)/usr/local/share/man/man1/gomboc.1 2>&1)" && \
	  groff -man -Tutf8 -P-cbou $(STAGE)/usr/local/share/man/man1/gomboc.1 2>/dev/null | grep -q '^       run CASE' \
	  || { echo "example: the man page does not render without warnings"; exit 1; }
	cd / && PYTHONPATH=$(STAGE)$(subst $(PREFIX),/usr/local,$(PYDIR)) $(PYTHON) $(abspath examples/python_run.py) $(abspath cases/table1-gomboc-I.ini)
	@$(MAKE) --no-print-directory uninstall DESTDIR=$(STAGE) PREFIX=/usr/local > /dev/null
	@left=$$(find $(STAGE) -type f -o -type l); test -z "$$left" || { echo "uninstall left: $$left"; exit 1; }
	@echo "example: built and run against the staged shared library (soname $(SONAME)) and, through pkg-config --static, the static one; every installed header compiles on its own; the command linked against the shared library runs; the Python package runs from the install; man page renders; uninstall leaves no file"

# `make check` is `make verify`, by the usual name.
check: verify

# What `make install` put under $(DESTDIR)$(PREFIX), removed (directories it made are removed when empty).
uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/gomboc $(DESTDIR)$(PREFIX)/bin/gomboc-prove $(DESTDIR)$(PREFIX)/lib/libgomboc.a $(DESTDIR)$(PREFIX)/lib/pkgconfig/gomboc.pc
	rm -f $(DESTDIR)$(PREFIX)/lib/$(notdir $(SOLIB)) $(DESTDIR)$(PREFIX)/lib/$(SONAME) $(DESTDIR)$(PREFIX)/lib/libgomboc.so
	rm -f $(DESTDIR)$(PREFIX)/share/man/man1/gomboc.1
	rm -f $(addprefix $(DESTDIR)$(PREFIX)/include/gomboc/,$(notdir $(PUBLIC_HEADERS)))
	rm -f $(DESTDIR)$(PREFIX)/share/gomboc/scene-keys.md $(DESTDIR)$(PREFIX)/share/gomboc/outputs.md $(DESTDIR)$(PREFIX)/share/gomboc/CHANGELOG.md
	rm -f $(addprefix $(DESTDIR)$(PREFIX)/share/gomboc/reports/,$(notdir $(SHARE_REPORTS)))
	rm -f $(DESTDIR)$(PYDIR)/gomboc/__init__.py $(DESTDIR)$(PYDIR)/gomboc/plot.py
	rm -rf $(DESTDIR)$(PYDIR)/gomboc/__pycache__
	-rmdir $(DESTDIR)$(PREFIX)/include/gomboc $(DESTDIR)$(PREFIX)/share/gomboc/reports $(DESTDIR)$(PREFIX)/share/gomboc \
	  $(DESTDIR)$(PYDIR)/gomboc 2>/dev/null

help:
	@echo "make run          the default scenes (Table 1, both bodies) and their report: reports/out/runs.md"
	@echo "make verify       build, run every check and write reports/out/verification.md (make check: the same)"
	@echo "make verify-full  make verify plus the long studies and the ensembles of make study"
	@echo "make bench        speed ratios measured side by side in one run"
	@echo "make scans        the parameter maps of Figs 10-13 (cases/scans)"
	@echo "make study        the ensembles of cases/studies (random initial attitudes)"
	@echo "make prove        the statements proved on Arb's ball arithmetic (docs/proofs.md)"
	@echo "make mpi          scans on MPI ranks (installs OpenMPI)"
	@echo "make fuzz | sanitize | valgrind   the robustness gates"
	@echo "make references   regenerate references/*.json with scipy and sympy"
	@echo "make install | uninstall          the command, static and shared library, headers, pkg-config file and man page under PREFIX"
	@echo "make example      the library's example and a C++ program against a staged install"
	@echo "make clean        remove the build and the reports, keeping the long results (scans, study, gates)"
	@echo "make distclean    remove those too"
	@echo "Debian packages missing are installed by every target that needs them (as root)." 

# The long results (make scans, make study: tens of minutes) and the gates' stamps stay; distclean removes them.
LONG_RESULTS := scans study gates
clean:
	rm -rf $(BUILD) build-san $(FUZZ_DIR)
	if [ -d $(OUT) ]; then find $(OUT) -mindepth 1 -maxdepth 1 $(LONG_RESULTS:%=! -name %) -exec rm -rf {} +; fi

distclean: clean
	rm -rf $(OUT)

# --- compilation
# The compiler and flags of the last build: an object is rebuilt when they change (WERROR, CFLAGS, CPPFLAGS).
FLAGS_STAMP := $(BUILD)/obj/flags
$(FLAGS_STAMP): FORCE | $(BUILD)/obj
	@printf '%s\n' '$(CC) $(ALL_CFLAGS) $(LDFLAGS)' > $@.tmp; cmp -s $@.tmp $@ && rm -f $@.tmp || mv $@.tmp $@

$(BUILD)/obj/%.o: src/%.c $(wildcard src/*.h) $(FLAGS_STAMP) | $(BUILD)/obj
	$(CC) $(ALL_CFLAGS) -c $< -o $@

# The library's symbols are hidden but for its public API (GB_API, src/gb_export.h): libgomboc.so exports
# nothing else (make verify compares `nm -D` with the marked declarations: scripts/check_exports.py).
$(CORE_OBJ) $(PIC_OBJ): ALL_CFLAGS += -fvisibility=hidden

$(BUILD)/pic/%.o: src/%.c $(wildcard src/*.h) $(FLAGS_STAMP)
	@mkdir -p $(BUILD)/pic
	$(CC) $(ALL_CFLAGS) -fPIC -c $< -o $@

$(SOLIB): $(PIC_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) $(LDFLAGS) -o $@ $^ $(CORE_LIBS)

# `gomboc --version`: the version (git describe) in a header rewritten only when it changes.
$(BUILD)/obj/gomboc.o: $(BUILD)/obj/gomboc_version.h
$(BUILD)/obj/gomboc.o: ALL_CFLAGS += -I$(BUILD)/obj
$(BUILD)/obj/gomboc_version.h: FORCE | $(BUILD)/obj
	@printf '#define GOMBOC_VERSION "%s"\n' '$(VERSION)' > $@.tmp; cmp -s $@.tmp $@ && rm -f $@.tmp || mv $@.tmp $@
FORCE:

$(BUILD)/obj/verify_%.o: verify/%.c $(wildcard src/*.h verify/*.h) $(FLAGS_STAMP) | $(BUILD)/obj
	$(CC) $(ALL_CFLAGS) -Iverify -c $< -o $@

# Made anew each time: an object whose source was removed must not stay in the archive.
$(LIB): $(CORE_OBJ)
	rm -f $@
	ar rcs $@ $^

$(BIN): $(filter-out $(PROVE_OBJ),$(CLI_OBJ)) $(LIB) | $(PROVE_BIN)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -o $@ $(filter-out $(FLAGS_STAMP),$^) -Wl,--as-needed $(CORE_LIBS)

$(PROVE_BIN): $(CLI_OBJ) $(LIB)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -o $@ $(filter-out $(FLAGS_STAMP),$^) $(CORE_LIBS)

# The harness runs independent long computations on the machine's threads where OpenMP is (s6_chaos).
$(BUILD)/obj/verify_s6_chaos.o: ALL_CFLAGS += $(OPENMP)
$(VERIFY_BIN): $(VERIFY_OBJ) $(LIB)
	$(CC) $(ALL_CFLAGS) $(OPENMP) $(LDFLAGS) -o $@ $^ $(TEST_LIBS) $(CORE_LIBS)

$(BENCH_BIN): $(BENCH_SRC) verify/bench/plain.c $(LIB) $(wildcard src/*.h verify/bench/*.h) | $(BUILD)/obj
	$(CC) $(ALL_CFLAGS) -fopenmp-simd -o $@ $(BENCH_SRC) verify/bench/plain.c $(LIB) $(CORE_LIBS)

$(BUILD)/mpi/gomboc_scan.o: src/gomboc_scan.c $(wildcard src/*.h)
	@mkdir -p $(BUILD)/mpi
	$(MPICC) $(ALL_CFLAGS) -DGOMBOC_MPI -c $< -o $@

$(MPI_BIN): $(filter-out %/gomboc_scan.o,$(CLI_OBJ)) $(BUILD)/mpi/gomboc_scan.o $(LIB)
	$(MPICC) $(ALL_CFLAGS) -o $@ $^ $(CORE_LIBS)

$(BUILD)/native/%.o: src/%.c $(wildcard src/*.h)
	@mkdir -p $(BUILD)/native
	$(CC) $(WARN) $(NATIVE_FLAGS) $(shell pkg-config --cflags $(PKGS)) $(SICONOS_CFLAGS) -Isrc -c $< -o $@

$(BUILD)/native/plain.o: verify/bench/plain.c verify/bench/plain.h $(wildcard src/*.h)
	@mkdir -p $(BUILD)/native
	$(CC) $(WARN) $(NATIVE_FLAGS) -fopenmp-simd $(shell pkg-config --cflags $(PKGS)) $(SICONOS_CFLAGS) -Isrc -c $< -o $@

$(BENCH_NATIVE): $(BENCH_SRC) $(BUILD)/native/plain.o $(NATIVE_OBJ) $(wildcard src/*.h verify/bench/*.h)
	$(CC) $(WARN) $(NATIVE_FLAGS) $(shell pkg-config --cflags $(PKGS)) $(SICONOS_CFLAGS) -Isrc -o $@ $(BENCH_SRC) $(BUILD)/native/plain.o $(NATIVE_OBJ) $(CORE_LIBS)

$(BUILD)/obj:
	mkdir -p $@
