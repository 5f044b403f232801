# coordinator/coordinator.mk - fragment for the top-level Makefile:
#   include coordinator/coordinator.mk     (after TOP, BUILD, BIN, JOBS are set)
# Defines the phony target `coordinator`, which builds $(BIN)/fc-master and $(BIN)/fc-slave.

.PHONY: coordinator coordinator-clean

coordinator:
	$(MAKE) -C $(TOP)/coordinator -j$(JOBS) BIN=$(BIN) OBJDIR=$(BUILD)/coordinator

coordinator-clean:
	$(MAKE) -C $(TOP)/coordinator BIN=$(BIN) OBJDIR=$(BUILD)/coordinator clean
