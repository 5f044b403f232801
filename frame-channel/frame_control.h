/*******************************************************************************
 * frame_control.h
 *
 * Frame control: another program (fc-slave) says, frame by frame, what this
 * process renders, so one POV-Ray process can serve many pieces of work and
 * parse each frame once for all the tiles it holds.
 *
 * Frame_Control=PATH names a file, FIFO or /dev/fd/N. Before parsing a frame
 * the front end reads one line (blocking) unless an earlier line is pending;
 * control_line.h has the format: "render N [rectangles]" renders frame N,
 * skipping the frames before it without parsing them, and with rectangles
 * traces only the render blocks that meet one of them, on the block grid of
 * the whole render area, so their pixels equal a render of the whole area
 * under every antialiasing method; "stop" (or the end of the file) ends the
 * render successfully. A line naming a frame that has already passed is an
 * error.
 *
 * POV-Ray front-end code, run by the renderer (povray-fc); vfe/vfe.cpp calls it.
 * This file is part of povray-fc and is licensed like POV-Ray (AGPL-3.0).
 *******************************************************************************/

#ifndef FRAME_CHANNEL_FRAME_CONTROL_H
#define FRAME_CHANNEL_FRAME_CONTROL_H

#include <string>
#include <vector>

#include "base/povmscpp.h"

namespace vfe
{
  class FrameControl
  {
    public:
      enum Action { kRender, kSkip, kStop };

      // The process-wide control (one render per process).
      static FrameControl& Get();

      // Opens the control named by Frame_Control in opts, if any; throws on failure.
      void Open(POVMS_Object& opts);
      bool Active() const { return m_Fd >= 0; }
      void Close();

      // What to do with frame `frame`. kRender sets (or clears) the frame's render
      // rectangles in frameOptions. Throws on a malformed line or a frame that passed.
      Action Next(int frame, POVMS_Object& frameOptions);

    private:
      FrameControl() : m_Fd(-1), m_Pending(false), m_PendingFrame(0) {}

      bool ReadLine(std::string& line);

      int m_Fd;
      std::string m_Path;
      std::string m_Buffer;
      bool m_Pending;                       // a "render" line not reached yet
      int m_PendingFrame;
      std::vector<POVMSInt> m_PendingRects;
  };
}

#endif // FRAME_CHANNEL_FRAME_CONTROL_H
