# coordinator/coordinator.mk - fragment for the top-level Makefile:
#   include coordinator/coordinator.mk     (after TOP, BUILD, BIN, JOBS are set)
# Defines the phony targets `coordinator` (builds $(BIN)/fc-master, fc-slave and fc-image.so
# with CMake, coordinator/CMakeLists.txt) and `coordinator-unit-test` (the units' GoogleTest
# cases, run by ctest). fc-image-writer, which links POV-Ray, is built by
# image-writer/image-writer.mk.

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
