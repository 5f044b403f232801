# frame-channel/frame-channel.mk - fragment for the top-level Makefile (after POV_TREE,
# STAMPS and pov_compile are set): the renderer's frame channel and frame control,
# libframechannel.a. They are POV-Ray front-end code, compiled as POV-Ray compiles its vfe/
# sources (pov_compile), so they wait for the patched, configured tree; the library goes
# into POV-Ray's link through LIBS.

FRAME_CHANNEL_BUILD := $(BUILD)/frame-channel
FRAME_CHANNEL_LIB := $(FRAME_CHANNEL_BUILD)/libframechannel.a
FRAME_CHANNEL_OBJS := $(addprefix $(FRAME_CHANNEL_BUILD)/,frame_channel.o frame_control.o \
  frame_record.o control_line.o parse_reads.o)
# POV-Ray's headers change only with the series (the patched stamp); ours with their files.
FRAME_CHANNEL_HEADERS := $(wildcard $(TOP)/frame-channel/*.h $(TOP)/speedups/*.h)

$(FRAME_CHANNEL_BUILD)/%.o: $(TOP)/frame-channel/%.cpp $(FRAME_CHANNEL_HEADERS) \
  $(STAMPS)/patched $(STAMPS)/configured
	mkdir -p $(@D)
	$(call pov_compile,$<,$@)

$(FRAME_CHANNEL_LIB): $(FRAME_CHANNEL_OBJS)
	rm -f $@ && ar rcs $@ $^
