/*******************************************************************************
 * option_ids.h
 *
 * POVMS attribute ids of povray-fc's Frame_Channel and Frame_Control options and of
 * the render rectangles the frame control sets per frame. Lower-case ids: POV-Ray's
 * own (base/povmsgid.h) never start that way, and keeping them here avoids touching
 * a header that every POV-Ray file includes. Included by POV-Ray's option table, its
 * view (which renders only the blocks meeting the rectangles) and this folder.
 *
 * This file is part of povray-fc and is licensed like POV-Ray (AGPL-3.0).
 *******************************************************************************/

#ifndef FRAME_CHANNEL_OPTION_IDS_H
#define FRAME_CHANNEL_OPTION_IDS_H

enum
{
	kPOVAttrib_FrameChannel     = 'dsCh', // UCS2 string: Frame_Channel, file or fd receiving frame records
	kPOVAttrib_FrameControl     = 'dsCt', // UCS2 string: Frame_Control, file or fd saying what to render per frame
	kPOVAttrib_RenderRectangles = 'dsRR'  // int vector: x0,y0,x1,y1,... (0-based, half-open): render only the blocks meeting them
};

#endif // FRAME_CHANNEL_OPTION_IDS_H
