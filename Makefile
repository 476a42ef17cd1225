# Tumble — the only build entry point.
#   make            build libtumble.so / libtumble.a (SPIR-V embedded) and the tools
#   make deps [DEPS="build run test video window"]  install missing Debian packages
#                   (default: build run test; run, bench and video check their own first)
#   make test       build and run the tests on lavapipe with the validation layers on
#   make install [PREFIX=/usr/local] [DESTDIR=] [INSTALL_LIBS="shared static"]
#                   headers, libtumble.so.X.Y.Z with its soname links, libtumble.a, tumble.pc
#   make examples   build examples/ against a temporary install, through pkg-config
#   make abi-check  compare libtumble.so with the ABI baseline in abi/ (part of make test)
#   make check-layers  the include arrows of src/ run one way (DESIGN.md §2; part of make test)
#   make run        install, build, run the default scene
#   make bench SCENE=freefall N=100000 STEPS=200 [BROADPHASE=grid|sap|lbvh|isap]
#              [FRAMES=dir EVERY=k CONTACTS=1]
#   make video SCENE=freefall N=2000 STEPS=240 [CONTACTS=1]  (build/freefall.mp4; needs ffmpeg)
#   make clean
# V=1 shows whole commands.

CC      ?= cc
BUILD   ?= build
CFLAGS  ?= -O2 -g
WARN    := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes
CSTD    := -std=c99 -D_POSIX_C_SOURCE=200809L
INCS    := -Iinclude -Iabi -Iglsl/common -Isrc -I$(BUILD)
# libshaderc as Debian 12 ships it: its shared library leaves glslang unresolved, so the
# static one and glslang's static libraries go in (hidden by the version script).
SHADERC_LIBS := -lshaderc_combined -lglslang -lMachineIndependent -lOSDependent \
                -lGenericCodeGen -lOGLCompiler -lSPIRV -lSPIRV-Tools-opt -lSPIRV-Tools \
                -lstdc++ -lpthread
LIBS    := -lvulkan $(SHADERC_LIBS) -ldl -lm
# The version, read from tumble.h: the shared library is libtumble.so.MAJOR.MINOR.PATCH with
# the soname libtumble.so.MAJOR; libtumble.so links to it, in the build tree and installed.
version_part = $(shell sed -n 's/^\#define TB_VERSION_$(1) \([0-9][0-9]*\).*/\1/p' include/tumble.h)
VERSION := $(call version_part,MAJOR).$(call version_part,MINOR).$(call version_part,PATCH)
SONAME  := libtumble.so.$(call version_part,MAJOR)
GLSLANG ?= glslangValidator
SPIRVVAL ?= spirv-val

ifeq ($(V),1)
Q :=
say = @true
else
Q := @
say = @printf '  %-8s %s\n' $(1) $(2)
endif

LIB_SRC    := $(shell find src -name '*.c' | sort)
LIB_OBJ    := $(LIB_SRC:%.c=$(BUILD)/obj/%.o)
SHADERS    := $(shell find glsl -name '*.comp' | sort)
SPV        := $(SHADERS:glsl/%.comp=$(BUILD)/spv/%.spv)
SCENES_SRC := $(wildcard tools/scenes/*.c)
TEST_SRC   := $(sort $(wildcard tests/test_*.c))
TEST_CXX   := $(sort $(wildcard tests/test_*.cpp))
TEST_BIN   := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%) $(TEST_CXX:tests/%.cpp=$(BUILD)/tests/%)
CXX        ?= g++
TOOLS      := $(BUILD)/bench $(BUILD)/tumble-run $(BUILD)/bench-prims $(BUILD)/bench-distance \
              $(BUILD)/bench-soak
PLUGINS := $(BUILD)/plugins/tb_blast.so $(BUILD)/plugins/tb_blast_glsl.so $(BUILD)/plugins/tb_contact_logger.so
REFUSED_PLUGINS := newer no_entry not_spirv bad_spirv bad_glsl pairs_early huge_stage glsl_dir
TEST_PLUGINS := $(REFUSED_PLUGINS:%=$(BUILD)/tests/plugins/refused_%.so) $(BUILD)/tests/plugins/broken.comp \
                $(BUILD)/tests/plugins/count_events.so $(BUILD)/tests/plugins/nested_step.so \
                $(BUILD)/tests/plugins/poison.so $(BUILD)/tests/plugins/poison.comp
RENDER_SHADERS := $(sort $(wildcard tools/render/shaders/*.vert tools/render/shaders/*.frag tools/render/shaders/*.comp))
RENDER_SPV     := $(RENDER_SHADERS:tools/render/shaders/%=$(BUILD)/render-spv/%.spv)
RENDER_SRC     := $(sort $(wildcard tools/render/*.c)) $(BUILD)/render_shaders.c
# GLFW is optional: with it, the renderer can open a window (tumble-run --window).
HAVE_GLFW  := $(shell pkg-config --exists glfw3 2>/dev/null && echo 1)
RENDER_LIBS := -lpng $(if $(HAVE_GLFW),$(shell pkg-config --libs glfw3))
RENDER_DEFS := $(if $(HAVE_GLFW),-DTR_HAVE_GLFW)

.PHONY: all deps test test-build test-run run bench video clean install check-install check-exports check-readme abi-check abi-baseline check-abi-break check-python wheel check-layers print-libs examples check-examples sanitize fuzz FORCE
.SECONDARY:
all: $(BUILD)/libtumble.so $(BUILD)/libtumble.a $(TOOLS) $(PLUGINS)

deps:
	$(Q)sh tools/deps $(DEPS)

# --- shaders: GLSL -> SPIR-V (optimised, validated) -> C array embedded in the library ---
$(BUILD)/spv/%.spv: glsl/%.comp
	$(call say,GLSL,$<)
	@mkdir -p $(dir $@)
	$(Q)$(GLSLANG) -V --target-env vulkan1.2 -Iglsl/common --quiet --depfile $@.d -o $@ $< >/dev/null
	$(Q)$(SPIRVVAL) --target-env vulkan1.2 $@

# One table of every embedded shader, named by its path under glsl/ without extension.
$(BUILD)/shaders.c: $(SPV) tools/embed-spirv Makefile
	$(call say,GEN,$@)
	$(Q)sh tools/embed-spirv gpu/shaders.h tb_shader_blob tb_shader_blobs $(BUILD)/spv $(SHADERS:glsl/%.comp=%) > $@

# Headers a shader compiled at run time can always include (a plugin's GLSL stages).
GLSL_HEADERS := abi/tumble_plugin.glsl glsl/common/layout.h
$(BUILD)/glsl_headers.c: $(GLSL_HEADERS) tools/embed-text Makefile
	$(call say,GEN,$@)
	@mkdir -p $(dir $@)
	$(Q)sh tools/embed-text gpu/glsl.h tb_glsl_header tb_glsl_headers $(GLSL_HEADERS) > $@

# --- renderer shaders (tools/render): the same path, one table of their own -------------
$(BUILD)/render-spv/%.spv: tools/render/shaders/%
	$(call say,GLSL,$<)
	@mkdir -p $(dir $@)
	$(Q)$(GLSLANG) -V --target-env vulkan1.2 -Iglsl/common -Itools/render/shaders --quiet --depfile $@.d -o $@ $< >/dev/null
	$(Q)$(SPIRVVAL) --target-env vulkan1.2 $@

# What the renderer was built with (GLFW or not): the tools relink when it changes, e.g.
# after `sh tools/deps window`.
$(BUILD)/render-config: FORCE
	@mkdir -p $(BUILD)
	@echo 'glfw=$(HAVE_GLFW)' | cmp -s - $@ || echo 'glfw=$(HAVE_GLFW)' > $@

$(BUILD)/render_shaders.c: $(RENDER_SPV) tools/embed-spirv Makefile $(BUILD)/render-config
	$(call say,GEN,$@)
	$(Q)sh tools/embed-spirv render_shaders.h tr_shader_blob tr_shader_blobs $(BUILD)/render-spv $(RENDER_SHADERS:tools/render/shaders/%=%) > $@

# --- library ----------------------------------------------------------------------------
$(BUILD)/obj/%.o: %.c
	$(call say,CC,$<)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CSTD) $(CFLAGS) $(WARN) $(INCS) -fPIC -fvisibility=hidden -DTB_BUILDING_LIBRARY -MMD -MP -c -o $@ $<

$(BUILD)/obj/%.o: $(BUILD)/%.c
	$(call say,CC,$<)
	$(Q)$(CC) $(CSTD) $(CFLAGS) $(INCS) -fPIC -fvisibility=hidden -c -o $@ $<

EMBEDDED_OBJ := $(BUILD)/obj/shaders.o $(BUILD)/obj/glsl_headers.o

$(BUILD)/libtumble.so.$(VERSION): $(LIB_OBJ) $(EMBEDDED_OBJ) abi/tumble.map
	$(call say,LD,$@)
	$(Q)$(CC) -shared -o $@ $(LIB_OBJ) $(EMBEDDED_OBJ) -Wl,--version-script=abi/tumble.map -Wl,-soname,$(SONAME) $(LIBS)

$(BUILD)/libtumble.so: $(BUILD)/libtumble.so.$(VERSION)
	$(Q)ln -sf libtumble.so.$(VERSION) $(BUILD)/$(SONAME) && ln -sf $(SONAME) $@

$(BUILD)/libtumble.a: $(LIB_OBJ) $(EMBEDDED_OBJ)
	$(call say,AR,$@)
	$(Q)rm -f $@ && ar rcs $@ $^

# --- install: headers, the libraries, tumble.pc ------------------------------------------
PREFIX     ?= /usr/local
LIBDIR     ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
GLSLDIR    ?= $(PREFIX)/share/tumble/glsl
INSTALL_LIBS ?= shared static
DESTDIR    ?=

$(BUILD)/tumble.pc: tools/install/tumble.pc.in include/tumble.h Makefile FORCE
	@sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' -e 's|@INCLUDEDIR@|$(INCLUDEDIR)|' \
	    -e 's|@GLSLDIR@|$(GLSLDIR)|' -e 's|@VERSION@|$(VERSION)|' \
	    -e 's|@LIBS_PRIVATE@|$(SHADERC_LIBS) -ldl -lm|' $< > $@.tmp && mv $@.tmp $@

install: $(BUILD)/libtumble.so $(BUILD)/libtumble.a $(BUILD)/tumble.pc
	$(call say,INSTALL,$(DESTDIR)$(PREFIX))
	$(Q)install -d $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(GLSLDIR)
	$(Q)install -m 644 include/tumble.h include/tumble_vulkan.h abi/tumble_plugin.h $(DESTDIR)$(INCLUDEDIR)
	$(Q)install -m 644 abi/tumble_plugin.glsl glsl/common/layout.h $(DESTDIR)$(GLSLDIR)
	$(Q)install -m 644 $(BUILD)/tumble.pc $(DESTDIR)$(LIBDIR)/pkgconfig/tumble.pc
	$(Q)if echo "$(INSTALL_LIBS)" | grep -qw static; then \
	  install -m 644 $(BUILD)/libtumble.a $(DESTDIR)$(LIBDIR); fi
	$(Q)if echo "$(INSTALL_LIBS)" | grep -qw shared; then \
	  install -m 755 $(BUILD)/libtumble.so.$(VERSION) $(DESTDIR)$(LIBDIR) && \
	  ln -sf libtumble.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(SONAME) && \
	  ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libtumble.so; fi

# make install must give a library others can build with: install into a temporary prefix,
# build the README's example against it through pkg-config and run it (shared library, only
# the prefix's lib dir on the loader's path), and link it statically from a static-only
# prefix through pkg-config --static.
INSTALL_TEST := $(abspath $(BUILD))/install-test
check-install: $(BUILD)/libtumble.so $(BUILD)/libtumble.a $(BUILD)/readme/example.c
	$(call say,CHECK,install)
	$(Q)rm -rf $(INSTALL_TEST)
	$(Q)$(MAKE) --no-print-directory -s install PREFIX=$(INSTALL_TEST)/shared >/dev/null
	$(Q)$(MAKE) --no-print-directory -s install PREFIX=$(INSTALL_TEST)/static INSTALL_LIBS=static >/dev/null
	$(Q)export PKG_CONFIG_PATH=$(INSTALL_TEST)/shared/lib/pkgconfig; \
	  $(CC) $(CSTD) $(WARN) -Werror -o $(INSTALL_TEST)/example-shared $(BUILD)/readme/example.c \
	    $$(pkg-config --cflags --libs tumble) && \
	  [ "$$(pkg-config --modversion tumble)" = $(VERSION) ] && \
	  readelf -d $(INSTALL_TEST)/example-shared | grep -q 'NEEDED.*$(SONAME)' && \
	  env $(TEST_ENV) LD_LIBRARY_PATH=$(INSTALL_TEST)/shared/lib $(INSTALL_TEST)/example-shared >/dev/null
	$(Q)export PKG_CONFIG_PATH=$(INSTALL_TEST)/static/lib/pkgconfig; \
	  $(CC) $(CSTD) $(WARN) -Werror -o $(INSTALL_TEST)/example-static $(BUILD)/readme/example.c \
	    $$(pkg-config --static --cflags --libs tumble) && \
	  ! readelf -d $(INSTALL_TEST)/example-static | grep -q 'NEEDED.*libtumble' && \
	  env $(TEST_ENV) $(INSTALL_TEST)/example-static >/dev/null

# examples/ built as a user builds them: against a temporary install, through pkg-config;
# make test runs them (check-examples).
EXAMPLES_DIR    := $(abspath $(BUILD))/examples
EXAMPLES_PREFIX := $(EXAMPLES_DIR)/prefix
EXAMPLE_PROGRAMS := hello pile hull contacts plugin
examples: $(BUILD)/libtumble.so $(BUILD)/libtumble.a
	$(call say,BUILD,examples)
	$(Q)rm -rf $(EXAMPLES_DIR) && mkdir -p $(EXAMPLES_DIR)
	$(Q)$(MAKE) --no-print-directory -s install PREFIX=$(EXAMPLES_PREFIX) >/dev/null
	$(Q)export PKG_CONFIG_PATH=$(EXAMPLES_PREFIX)/lib/pkgconfig; \
	  for e in $(EXAMPLE_PROGRAMS); do \
	    $(CC) $(CSTD) $(WARN) -Werror -o $(EXAMPLES_DIR)/$$e examples/$$e.c \
	      $$(pkg-config --cflags --libs tumble) -lm || exit 1; \
	  done; \
	  $(CC) $(CSTD) $(WARN) -Werror -shared -fPIC -o $(EXAMPLES_DIR)/plugin_counter.so \
	    examples/plugin_counter.c $$(pkg-config --cflags tumble)

check-examples: examples
	$(call say,CHECK,examples)
	$(Q)cd $(EXAMPLES_DIR) && for e in $(EXAMPLE_PROGRAMS); do \
	  env $(TEST_ENV) LD_LIBRARY_PATH=$(EXAMPLES_PREFIX)/lib ./$$e > $$e.out 2>&1 || \
	    { cat $$e.out; echo "examples/$$e.c failed"; exit 1; }; \
	done

FORCE:

# The libraries a program linked with build/libtumble.a needs after it.
print-libs:
	@echo $(LIBS)

# --- tools and tests --------------------------------------------------------------------
TOOL_CFLAGS := $(CSTD) $(CFLAGS) $(WARN) -Iinclude -Iabi -Itools/scenes -Itools/render -Itools/render/shaders -Itools/run -Itests -Iglsl/common -I$(BUILD) $(RENDER_DEFS)
TOOL_DEPS   := $(SCENES_SRC) $(RENDER_SRC) $(wildcard tools/render/*.h tools/render/shaders/*.h tools/scenes/*.h tools/run/*.h) $(BUILD)/libtumble.a
TOOL_LINK   := $(SCENES_SRC) $(RENDER_SRC) $(BUILD)/libtumble.a $(RENDER_LIBS) $(LIBS)

$(BUILD)/bench: tools/bench/bench.c $(TOOL_DEPS)
	$(call say,LD,$@)
	$(Q)$(CC) $(TOOL_CFLAGS) -o $@ tools/bench/bench.c $(TOOL_LINK)

# GPU time of the parallel primitives; it uses the library's internals, as the tests do.
$(BUILD)/bench-prims: tools/bench/prims.c $(BUILD)/libtumble.a
	$(call say,LD,$@)
	$(Q)$(CC) $(TOOL_CFLAGS) -Isrc -o $@ tools/bench/prims.c $(BUILD)/libtumble.a $(LIBS)

# Distance queries per second (tb_world_query_distances), through the public API.
$(BUILD)/bench-distance: tools/bench/distance.c tests/convex_reference.h $(BUILD)/libtumble.a
	$(call say,LD,$@)
	$(Q)$(CC) $(TOOL_CFLAGS) -o $@ tools/bench/distance.c $(BUILD)/libtumble.a $(LIBS) -lm

# A long run reporting NaN, energy and memory at intervals.
$(BUILD)/bench-soak: tools/bench/soak.c $(TOOL_DEPS)
	$(call say,LD,$@)
	$(Q)$(CC) $(TOOL_CFLAGS) -o $@ tools/bench/soak.c $(TOOL_LINK)

$(BUILD)/tumble-run: tools/run/run.c $(TOOL_DEPS)
	$(call say,LD,$@)
	$(Q)$(CC) $(TOOL_CFLAGS) -o $@ tools/run/run.c $(TOOL_LINK)

# --- plugins (abi/tumble_plugin.h): the examples in tools/plugins, and those the tests
# must see refused (tests/plugins) --------------------------------------------------------
PLUGIN_CFLAGS := $(CSTD) $(CFLAGS) $(WARN) -Iinclude -Iabi -Iglsl/common -fPIC -shared -fvisibility=hidden

$(BUILD)/plugins/blast.spv: tools/plugins/blast.comp tools/plugins/blast.h abi/tumble_plugin.glsl glsl/common/layout.h
	$(call say,GLSL,$<)
	@mkdir -p $(dir $@)
	$(Q)$(GLSLANG) -V --target-env vulkan1.2 -Iabi -Iglsl/common --quiet -o $@ $< >/dev/null
	$(Q)$(SPIRVVAL) --target-env vulkan1.2 $@

$(BUILD)/plugins/blast_spirv.h: $(BUILD)/plugins/blast.spv
	$(Q)(echo "static const uint32_t blast_spirv[] = {"; \
	  od -An -v -tx4 $< | sed -e 's/ *\([0-9a-f]\{8\}\)/0x\1u,/g'; echo "};") > $@

$(BUILD)/plugins/tb_blast.so: tools/plugins/blast.c tools/plugins/blast.h $(BUILD)/plugins/blast_spirv.h abi/tumble_plugin.h
	$(call say,LD,$@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -I$(BUILD)/plugins -DBLAST_SPIRV='"blast_spirv.h"' -o $@ $< -lm

# The same plugin compiling its stage from blast.comp, found beside it, when it loads.
$(BUILD)/plugins/tb_blast_glsl.so: tools/plugins/blast.c tools/plugins/blast.h tools/plugins/blast.comp abi/tumble_plugin.h
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)cp tools/plugins/blast.comp tools/plugins/blast.h $(dir $@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -o $@ $< -lm

$(BUILD)/plugins/%.so: tools/plugins/%.c abi/tumble_plugin.h
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -o $@ $<

$(BUILD)/plugins/tb_contact_logger.so: tools/plugins/contact_logger.c abi/tumble_plugin.h
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -o $@ $<

$(BUILD)/tests/plugins/refused_%.so: tests/plugins/refused.c abi/tumble_plugin.h
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -DREFUSED=REFUSED_$$(echo $* | tr a-z A-Z) -o $@ $<

$(BUILD)/tests/plugins/count_events.so: tests/plugins/count_events.c abi/tumble_plugin.h
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -o $@ $<

$(BUILD)/tests/plugins/nested_step.so: tests/plugins/nested_step.c abi/tumble_plugin.h
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -o $@ $<

$(BUILD)/tests/plugins/poison.so: tests/plugins/poison.c abi/tumble_plugin.h
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(PLUGIN_CFLAGS) -o $@ $<

$(BUILD)/tests/plugins/poison.comp: tests/plugins/poison.comp
	@mkdir -p $(dir $@)
	$(Q)cp $< $@

$(BUILD)/tests/plugins/broken.comp: tests/plugins/broken.comp
	@mkdir -p $(dir $@)
	$(Q)cp $< $@

# A C++ translation unit that includes tumble.h: the header must be C++-clean.
$(BUILD)/tests/%: tests/%.cpp include/tumble.h abi/tumble_plugin.h $(BUILD)/libtumble.a
	$(call say,CXX,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CXX) -std=c++11 -O2 -Wall -Wextra -Wpedantic -Werror -Iinclude -Iabi -o $@ $< $(BUILD)/libtumble.a $(LIBS)

$(BUILD)/tests/test_distance: tests/convex_reference.h
# The test plugins that call the C API find it in the test binary.
$(BUILD)/tests/test_plugin: TOOL_LINK += -rdynamic

$(BUILD)/tests/%: tests/%.c tests/harness.c tests/harness.h $(TOOL_DEPS)
	$(call say,LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(TOOL_CFLAGS) -Isrc -DTB_BUILD_DIR='"$(abspath $(BUILD))"' -DTB_SOURCE_DIR='"$(CURDIR)"' -o $@ $< tests/harness.c $(TOOL_LINK) -lcmocka

# --- sanitizers and fuzzing (Debian's clang) ---------------------------------------------
# The library again, built by clang with AddressSanitizer and UBSan (any report stops the
# program; tests/lsan.supp names the leaks that are the driver's): the API tests linked to
# it (SAN_TESTS) run in make test, and so does a minute of the libFuzzer target
# tests/fuzz/fuzz_api.c (tools/fuzz). `make fuzz SECONDS=N` runs that target for N
# seconds, growing a corpus in build/fuzz/corpus from the seeds in tests/fuzz/corpus.
SAN_CC    ?= clang-14
SAN_FLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
# The library's code also feeds the fuzzer's coverage (fuzzer-no-link).
SAN_LIB_FLAGS := $(SAN_FLAGS) -fsanitize=fuzzer-no-link
SAN       := $(BUILD)/san
SAN_OBJ   := $(LIB_SRC:%.c=$(SAN)/obj/%.o) $(SAN)/obj/shaders.o $(SAN)/obj/glsl_headers.o
SAN_TESTS := $(addprefix $(SAN)/tests/,test_api test_hull test_mesh)
FUZZ_BIN  := $(SAN)/fuzz_api $(SAN)/fuzz_plugin.so
SECONDS   ?= 60

$(SAN)/obj/%.o: %.c
	$(call say,SAN-CC,$<)
	@mkdir -p $(dir $@)
	$(Q)$(SAN_CC) $(CSTD) $(SAN_LIB_FLAGS) $(WARN) $(INCS) -DTB_BUILDING_LIBRARY -MMD -MP -c -o $@ $<

$(SAN)/obj/%.o: $(BUILD)/%.c
	$(call say,SAN-CC,$<)
	@mkdir -p $(dir $@)
	$(Q)$(SAN_CC) $(CSTD) $(SAN_LIB_FLAGS) $(INCS) -c -o $@ $<

$(SAN)/libtumble.a: $(SAN_OBJ)
	$(call say,AR,$@)
	$(Q)rm -f $@ && ar rcs $@ $^

$(SAN)/tests/%: tests/%.c tests/harness.c tests/harness.h $(SAN)/libtumble.a
	$(call say,SAN-LD,$@)
	@mkdir -p $(dir $@)
	$(Q)$(SAN_CC) $(CSTD) $(SAN_FLAGS) $(WARN) -Iinclude -Iabi -Itests -Iglsl/common -Isrc -I$(BUILD) \
	  -DTB_BUILD_DIR='"$(abspath $(BUILD))"' -DTB_SOURCE_DIR='"$(CURDIR)"' -o $@ $< tests/harness.c \
	  $(SAN)/libtumble.a $(LIBS) -lcmocka

FUZZ_SRC := tests/fuzz/fuzz_api.c tests/fuzz/describe.c
$(SAN)/fuzz_api: $(FUZZ_SRC) tests/fuzz/input.h tests/fuzz/describe.h $(SAN)/libtumble.a
	$(call say,SAN-LD,$@)
	$(Q)$(SAN_CC) $(CSTD) $(SAN_FLAGS) -fsanitize=fuzzer $(WARN) -Iinclude -Iabi -Itests/fuzz \
	  -DTB_SOURCE_DIR='"$(CURDIR)"' -o $@ $(FUZZ_SRC) $(SAN)/libtumble.a $(LIBS)

$(SAN)/fuzz_plugin.so: tests/fuzz/plugin.c abi/tumble_plugin.h
	$(call say,CC,$@)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CSTD) $(CFLAGS) $(WARN) -Iinclude -Iabi -shared -fPIC -o $@ $<

sanitize: $(SAN_TESTS) $(FUZZ_BIN)

fuzz: deps
	$(Q)$(MAKE) --no-print-directory -j$(BUILD_JOBS) $(FUZZ_BIN)
	$(Q)env $(TEST_ENV) sh tools/fuzz $(SAN) $(SECONDS) $(BUILD)/fuzz

# Tests run on lavapipe with the validation layers (synchronization validation included);
# any validation message fails a test. TEST_JOBS runs at a time (a run keeps about one core
# busy), the slowest first so that none is left running alone at the end (tools/run-tests).
# The tests of the kernels that work in subgroups (TEST_TWO_WIDTHS) run at lavapipe's two
# vector widths, subgroups of 8 and 4; the rest at one. Then the sanitizer build's API
# tests and a minute of fuzzing.
TEST_ENV := TUMBLE_DEVICE=$${TUMBLE_DEVICE:-llvmpipe} TUMBLE_VALIDATION=1 \
            LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
            UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
            TUMBLE_FUZZ_SAN=$(abspath $(SAN)) TUMBLE_FUZZ_WORK=$(abspath $(BUILD))/fuzz
TEST_LOGS := $(BUILD)/test-logs
TEST_JOBS ?= 2
TEST_TWO_WIDTHS := $(addprefix $(BUILD)/tests/,test_prims test_batching test_block test_broadphase \
                   test_narrowphase test_round test_mesh_contacts test_golden)
TEST_SLOWEST := $(BUILD)/tests/test_stacking tools/fuzz $(SAN)/tests/test_api $(BUILD)/tests/test_joints $(BUILD)/tests/test_joint_kinds \
                $(BUILD)/tests/test_joint_structures \
                $(addprefix $(BUILD)/tests/,test_round test_broadphase test_snapshot test_contacts \
                test_block test_narrowphase test_mesh_contacts test_integrate)
TEST_RUNS  := $(filter-out $(TEST_SLOWEST),$(TEST_BIN)) $(SAN_TESTS)
TEST_ORDER := $(foreach t,$(TEST_SLOWEST) $(filter-out $(TEST_SLOWEST),$(TEST_RUNS)),\
                $(if $(filter $(TEST_TWO_WIDTHS),$(t)),$(t),$(t)@256))
# What the tests run is built first with a job per core (on two cores about half the time);
# the checks and the runs follow in a make of their own, so that under `make -j` no target
# is built by two makes at once.
BUILD_JOBS ?= $(shell nproc 2>/dev/null || echo 1)
test-build: deps
	$(Q)$(MAKE) --no-print-directory -j$(BUILD_JOBS) all $(TEST_BIN) $(TEST_PLUGINS) $(SAN_TESTS) $(FUZZ_BIN)
test: deps test-build
	$(Q)$(MAKE) --no-print-directory test-run
test-run: check-layers all $(TEST_BIN) $(TEST_PLUGINS) $(SAN_TESTS) $(FUZZ_BIN) check-exports check-readme check-install check-examples abi-check check-abi-break check-python
	$(Q)env $(TEST_ENV) sh tools/run-tests $(TEST_LOGS) $(TEST_JOBS) $(TEST_ORDER)

# The ABI contract (abi/): libtumble.so compared with abi/libtumble.abi by libabigail's
# abidiff, on the types of the public headers. Added functions are compatible; any other
# change (a struct's layout, a signature, a removed function) fails. `make abi-baseline`
# records a new contract, on purpose only. Needs the library built with debug info (-g).
ABIDW   ?= abidw
ABIDIFF ?= abidiff
abi-check: $(BUILD)/libtumble.so
	$(call say,CHECK,ABI)
	$(Q)out=$$($(ABIDIFF) --no-added-syms --headers-dir2 include abi/libtumble.abi $< 2>&1) || { \
	  echo "$$out"; echo "abi-check: $< breaks the ABI recorded in abi/libtumble.abi"; exit 1; }

abi-baseline: $(BUILD)/libtumble.so
	$(Q)$(ABIDW) --headers-dir include --no-corpus-path --out-file abi/libtumble.abi $<

# abi-check must fail on an incompatible change: tools/abi-break-check makes one in a
# temporary copy (a field inserted into tb_world_def) and runs abi-check there.
check-abi-break: $(BUILD)/libtumble.so
	$(call say,CHECK,abi-break)
	$(Q)sh tools/abi-break-check $(BUILD)

# The Python package (tools/python) as a user installs it: `pip install tools/python` into a
# fresh virtual environment under build/, offline (numpy, cffi and pytest are Debian's,
# through --system-site-packages: make deps), finding the library of a temporary install
# through pkg-config; its pytest suite runs there, in two processes when pytest-xdist is
# there (Debian's python3-pytest-xdist, which make deps installs: 48 s instead of 87 on two
# cores). Then the wheel (make wheel) goes into the same environment and must open the
# library it bundles.
PYTHON      ?= /usr/bin/python3
PY_TEST     := $(abspath $(BUILD))/python-test
PIP_OFFLINE := --no-build-isolation --no-deps --no-index --disable-pip-version-check -q
PY_ENV      := env -u TUMBLE_LIBRARY -u TUMBLE_HEADER $(TEST_ENV) TUMBLE_BUILD_DIR=$(abspath $(BUILD))
PY_PROCESSES = $(shell $(PYTHON) -c 'import xdist' 2>/dev/null && echo '-n 2')
check-python: $(BUILD)/libtumble.so $(PLUGINS) wheel
	$(call say,PYTEST,tools/python)
	$(Q)rm -rf $(PY_TEST) && mkdir -p $(PY_TEST)/empty
	$(Q)$(MAKE) --no-print-directory -s install PREFIX=$(PY_TEST)/prefix >/dev/null
	$(Q)$(PYTHON) -m venv --system-site-packages $(PY_TEST)/venv
	$(Q)$(PY_TEST)/venv/bin/pip install $(PIP_OFFLINE) ./tools/python
	$(Q)cd $(PY_TEST) && $(PY_ENV) PKG_CONFIG_PATH=$(PY_TEST)/prefix/lib/pkgconfig venv/bin/python -c \
	  'import sys, tumble; assert tumble.__file__.startswith(sys.prefix) and tumble.library_source == "pkg-config", tumble.library_path'
	$(Q)$(PY_ENV) PKG_CONFIG_PATH=$(PY_TEST)/prefix/lib/pkgconfig $(PY_TEST)/venv/bin/python -m pytest -q -p no:cacheprovider $(PY_PROCESSES) tools/python
	$(Q)$(PY_TEST)/venv/bin/pip install $(PIP_OFFLINE) --force-reinstall $(BUILD)/wheel/tumble-*.whl
	$(Q)cd $(PY_TEST) && $(PY_ENV) PKG_CONFIG_PATH= PKG_CONFIG_LIBDIR=$(PY_TEST)/empty venv/bin/python -c \
	  'import tumble; assert tumble.library_source == "bundled", tumble.library_path; tumble.World().step()'

# A wheel of the Python package with build/libtumble.so (less its debug info) bundled in
# it: build/wheel/.
wheel: $(BUILD)/libtumble.so
	$(call say,WHEEL,$(BUILD)/wheel)
	$(Q)rm -rf $(BUILD)/wheel && mkdir -p $(BUILD)/wheel-lib
	$(Q)strip --strip-debug -o $(BUILD)/wheel-lib/libtumble.so.$(VERSION) $(BUILD)/libtumble.so.$(VERSION)
	$(Q)TUMBLE_BUNDLE_LIBRARY=$(abspath $(BUILD))/wheel-lib/libtumble.so.$(VERSION) $(PYTHON) -m pip wheel $(PIP_OFFLINE) -w $(BUILD)/wheel ./tools/python

# The include arrows of the C core (api -> world -> stages -> gpu -> base, geom -> base),
# each folder's main header, and tools kept to the public headers: tools/check-layers.
check-layers:
	$(call say,CHECK,layers)
	$(Q)sh tools/check-layers

# Only tb_* symbols may leave the shared library.
check-exports: $(BUILD)/libtumble.so
	$(call say,CHECK,exports)
	$(Q)bad=$$(nm -D --defined-only $< | awk '$$2 != "A" {print $$3}' | grep -v '^tb_' || true); \
	if [ -n "$$bad" ]; then echo "non-tb_ symbols exported: $$bad"; exit 1; fi

# The README's C example must compile warning-free and run.
$(BUILD)/readme/example.c: README.md
	@mkdir -p $(BUILD)/readme
	$(Q)awk '/^```c$$/{f=1;next} /^```$$/{f=0} f' README.md > $@

check-readme: $(BUILD)/libtumble.a $(BUILD)/readme/example.c
	$(call say,CHECK,README.md)
	$(Q)$(CC) $(CSTD) $(WARN) -Werror -Iinclude -o $(BUILD)/readme/example $(BUILD)/readme/example.c $(BUILD)/libtumble.a $(LIBS)
	$(Q)env $(TEST_ENV) $(BUILD)/readme/example >/dev/null

# run, bench and video check their packages before anything is built or run (a
# prerequisite would race the build under -j), then build through a sub-make.
run:
	$(Q)sh tools/deps run
	$(Q)$(MAKE) --no-print-directory all
	@mkdir -p $(BUILD)/run
	$(Q)$(BUILD)/tumble-run --png $(BUILD)/run/final.png

SCENE ?= freefall
N     ?= 0
STEPS ?= 0
bench:
	$(Q)sh tools/deps run
	$(Q)$(MAKE) --no-print-directory all
	$(Q)$(BUILD)/bench --scene $(SCENE) --n $(N) --steps $(STEPS) $(if $(BROADPHASE),--broadphase $(BROADPHASE)) $(if $(FRAMES),--frames $(FRAMES) --every $(or $(EVERY),1) $(if $(CONTACTS),--contacts))

# A video of a bench scene: make video SCENE=freefall N=2000 STEPS=240 (needs ffmpeg).
video:
	$(Q)sh tools/deps video
	$(Q)$(MAKE) --no-print-directory all
	@rm -rf $(BUILD)/frames/$(SCENE) && mkdir -p $(BUILD)/frames/$(SCENE)
	$(Q)$(BUILD)/bench --scene $(SCENE) --n $(N) --steps $(STEPS) --json-only --frames $(BUILD)/frames/$(SCENE) --every $(or $(EVERY),1) $(if $(CONTACTS),--contacts) >/dev/null
	$(Q)tools/render/video $(BUILD)/frames/$(SCENE) $(BUILD)/$(SCENE).mp4

clean:
	$(call say,RM,$(BUILD))
	$(Q)rm -rf $(BUILD)

-include $(LIB_OBJ:.o=.d) $(SAN_OBJ:.o=.d) $(SPV:=.d) $(RENDER_SPV:=.d)
