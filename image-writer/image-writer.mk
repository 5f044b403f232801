# image-writer/image-writer.mk - fragment for the top-level Makefile (after POV_TREE, BIN and
# pov_compile are set): fc-image-writer, fc-master's helper that runs POV-Ray's own Targa
# writer and dither handler (fc_image_writer.cpp says why). It is compiled as POV-Ray
# compiles its vfe/ sources and linked against the patched tree's libraries, with their
# LIBS, so it is built once POV-Ray is.

IMAGE_WRITER := $(BIN)/fc-image-writer
IMAGE_WRITER_OBJ := $(BUILD)/image-writer/fc_image_writer.o

all: $(IMAGE_WRITER)

$(IMAGE_WRITER_OBJ): $(TOP)/image-writer/fc_image_writer.cpp $(TOP)/image-writer/protocol.h \
  $(TOP)/frame-channel/frame_record.h $(TOP)/speedups/encode_memo.h $(BIN)/povray-fc
	mkdir -p $(@D)
	$(call pov_compile,$<,$@)

# POV-Ray's libraries depend on each other: one group. Its LIBS come from its configured Makefile.
$(IMAGE_WRITER): $(IMAGE_WRITER_OBJ) $(BIN)/povray-fc
	g++ $(POV_LDFLAGS) -Wl,--as-needed -pthread $(IMAGE_WRITER_OBJ) -o $@.tmp \
	  -Wl,--start-group $(POV_TREE)/source/libpovray.a $(POV_TREE)/vfe/libvfe.a $(FRAME_CHANNEL_LIB) \
	  $(FC_SCENE_LIB) $(FC_LIB) $(SPEEDUPS_LIB) -Wl,--end-group $$(sed -n 's/^LIBS = //p' $(POV_TREE)/unix/Makefile)
	mv $@.tmp $@
