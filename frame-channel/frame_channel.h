/*******************************************************************************
 * frame_channel.h
 *
 * The frame channel: hands every finished frame to another program (fc-slave)
 * as one record, instead of writing it to an image file.
 *
 * Frame_Channel=PATH names a file, FIFO or /dev/fd/N. Per finished frame the
 * front end writes one record (frame_record.h has the format): a header line,
 * then the pixels of the frame's rectangles, encoded exactly as the output
 * format's writer encodes them (gamma, dithering, bit depth), so the receiver
 * can assemble frames that equal POV-Ray's own output without decoding an
 * image file; a record of the whole image in Targa or PNG also carries the
 * file that writer makes of the frame. The rectangles are those Frame_Control
 * asked for (frame_control.h), else the whole image. Every record also says
 * which files the frame's parse read or looked for (parse_reads.h).
 *
 * With a channel set, no image file is written, nor the render state file
 * (NAME.pov-state): there is nothing to continue from.
 *
 * POV-Ray front-end code, run by the renderer (povray-fc); vfe/vfe.cpp calls it.
 * This file is part of povray-fc and is licensed like POV-Ray (AGPL-3.0).
 *******************************************************************************/

#ifndef FRAME_CHANNEL_FRAME_CHANNEL_H
#define FRAME_CHANNEL_FRAME_CHANNEL_H

#include <string>
#include <vector>

#include "base/povmscpp.h"
#include "base/types.h"
#include "base/image/image.h"
#include "frontend/imageprocessing.h"

namespace vfe
{
  using namespace pov_base;

  class FrameChannel
  {
    public:
      // The process-wide channel (one render per process).
      static FrameChannel& Get();

      // Opens the channel named by Frame_Channel in opts, if any, and turns the render
      // state file off; throws on failure.
      void Open(POVMS_Object& opts);
      bool Active() const { return m_Fd >= 0; }
      void Close();

      // Timing of the current frame: parse starts (and the files it reads are
      // collected afresh), render starts.
      void ParseStarted();
      void RenderStarted();

      // Keeps the statistics of the frame being rendered (from the render's
      // statistics message, which arrives before the render is done).
      void NoteStatistics(POVMS_Object& stats);

      // Writes the record of a finished frame, whose pixels are in
      // imageProcessing's image; throws on failure.
      void WriteFrame(POVMS_Object& frameOptions, pov_frontend::ImageProcessing& imageProcessing, int frame);

    private:
      FrameChannel() : m_Fd(-1), m_Rays(-1), m_ParseStart(0), m_RenderStart(0) {}

      void WriteAll(const void *data, size_t size);

      int m_Fd;
      std::string m_Path;
      POVMSLong m_Rays;
      double m_ParseStart;
      double m_RenderStart;
  };
}

#endif // FRAME_CHANNEL_FRAME_CHANNEL_H
