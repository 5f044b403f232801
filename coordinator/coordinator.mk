# coordinator/coordinator.mk - fragment for the top-level Makefile:
#   include coordinator/coordinator.mk     (after TOP, BUILD, BIN, JOBS are set)
# Defines the phony targets `coordinator` (builds $(BIN)/fc-master, fc-slave and fc-image.so
# with CMake, coordinator/CMakeLists.txt) and `coordinator-unit-test` (the units' GoogleTest
# cases, run by ctest).

.PHONY: coordinator coordinator-unit-test

COORD_BUILD := $(BUILD)/coordinator

$(COORD_BUILD)/CMakeCache.txt: $(TOP)/coordinator/CMakeLists.txt | deps
	cmake -S $(TOP)/coordinator -B $(COORD_BUILD) -DFC_BIN=$(BIN) \
	  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache >/dev/null

coordinator: $(COORD_BUILD)/CMakeCache.txt
	cmake --build $(COORD_BUILD) -j$(JOBS) --target fc-master fc-slave fc-image

coordinator-unit-test: $(COORD_BUILD)/CMakeCache.txt
	cmake --build $(COORD_BUILD) -j$(JOBS) --target coordinator_tests
	cd $(COORD_BUILD) && ctest --output-on-failure -j$(JOBS)

# fc-image-writer: POV-Ray's own Targa writer in a process of its own, for the frames fc-master
# assembles (coordinator/image_writer_main.cpp says why). Built against the patched POV-Ray
# tree, with its flags and libraries, once POV-Ray is built.
IMAGE_WRITER := $(BIN)/fc-image-writer
IMAGE_WRITER_OBJ := $(BUILD)/coordinator/image_writer_main.o
POV_INCLUDES = -DHAVE_CONFIG_H -I$(POV_TREE)/source -I$(POV_TREE)/unix -I$(POV_TREE)/source/base \
  -I$(POV_TREE)/vfe -I$(POV_TREE)/vfe/unix $(shell pkg-config --cflags OpenEXR 2>/dev/null)

all: $(IMAGE_WRITER)

$(IMAGE_WRITER_OBJ): $(TOP)/coordinator/image_writer_main.cpp $(TOP)/coordinator/image_writer_protocol.h \
  $(BIN)/povray-fc
	mkdir -p $(dir $@)
	PATH=$(CCACHE_PATH):$$PATH g++ $(POV_CXXFLAGS) -Wno-multichar $(POV_CPPFLAGS) $(POV_INCLUDES) -pthread -c $< -o $@

# POV-Ray's libraries depend on each other: one group. Its LIBS come from its configured Makefile.
$(IMAGE_WRITER): $(IMAGE_WRITER_OBJ) $(BIN)/povray-fc
	g++ $(POV_LDFLAGS) -Wl,--as-needed -pthread $(IMAGE_WRITER_OBJ) -o $@.tmp \
	  -Wl,--start-group $(POV_TREE)/source/libpovray.a $(POV_TREE)/vfe/libvfe.a $(FC_LIB) -Wl,--end-group \
	  $$(sed -n 's/^LIBS = //p' $(POV_TREE)/unix/Makefile)
	mv $@.tmp $@
