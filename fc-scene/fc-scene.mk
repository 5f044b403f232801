# fc-scene/fc-scene.mk - fragment for the top-level Makefile (after POV_TREE, STAMPS and
# pov_compile are set): frame coherence's code that reads POV-Ray's own objects,
# libfcscene.a. It includes POV-Ray's backend headers, so it is compiled as POV-Ray compiles
# its sources (pov_compile) once the tree is patched and configured; the library goes into
# POV-Ray's link through LIBS.

FC_SCENE_BUILD := $(BUILD)/fc-scene
FC_SCENE_LIB := $(FC_SCENE_BUILD)/libfcscene.a
FC_SCENE_OBJS := $(addprefix $(FC_SCENE_BUILD)/,scene_units.o corner_boxes.o mesh_faces.o tie_searches.o shadow_tests.o surface_hits.o)
# POV-Ray's headers change only with the series (the patched stamp); ours with their files.
FC_SCENE_HEADERS := $(wildcard $(TOP)/fc-scene/*.h $(TOP)/povray-fc/include/povrayfc/*.h)

$(FC_SCENE_BUILD)/%.o: $(TOP)/fc-scene/%.cpp $(FC_SCENE_HEADERS) $(STAMPS)/patched $(STAMPS)/configured
	mkdir -p $(@D)
	$(call pov_compile,$<,$@)

$(FC_SCENE_LIB): $(FC_SCENE_OBJS)
	rm -f $@ && ar rcs $@ $^
