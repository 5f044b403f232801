// POVMS attribute ids of povray-fc's render options (a C header: POV-Ray includes it).
// Lower-case 'fc..' ids: POV-Ray's own ids (base/povmsgid.h) never start that way,
// so keeping ours here avoids touching a header every POV-Ray file includes.
#ifndef POVRAYFC_POVMS_IDS_H
#define POVRAYFC_POVMS_IDS_H

enum
{
	kPOVAttrib_FrameCoherence      = 'fcOn',  /* bool: Frame_Coherence, +Y/-Y */
	kPOVAttrib_FrameCoherenceGrid  = 'fcGr',  /* int: Frame_Coherence_Grid, +YG: voxels on the longest axis, 0 = auto */
	kPOVAttrib_FrameCoherenceStats = 'fcSt',  /* string: Frame_Coherence_Stats, +YS: per-frame CSV file */
	kPOVAttrib_FrameCoherenceMask  = 'fcMk',  /* string: Frame_Coherence_Mask, +YM: folder for re-traced pixel masks */
	kPOVAttrib_FrameCoherenceFrame = 'fcFr'   /* int: the frame number, set per frame by the front end */
};

#endif
