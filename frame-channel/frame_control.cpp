/*******************************************************************************
 * frame_control.cpp
 *
 * Frame control (see frame_control.h): one line per frame (control_line.h),
 * read before the frame is parsed.
 *
 * This file is part of povray-fc and is licensed like POV-Ray (AGPL-3.0).
 *******************************************************************************/

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <unistd.h>

#include <cstdio>

#include "vfe.h"
#include "frame-channel/control_line.h"
#include "frame-channel/frame_control.h"
#include "frame-channel/option_ids.h"

// this must be the last file included
#include "base/povdebug.h"

namespace vfe
{

FrameControl& FrameControl::Get()
{
  static FrameControl control;
  return control;
}

void FrameControl::Open(POVMS_Object& opts)
{
  Close();
  std::string path(UCS2toASCIIString(opts.TryGetUCS2String(kPOVAttrib_FrameControl, "")));
  if (path.empty())
    return;
  m_Fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (m_Fd < 0)
  {
    // said here: the console reports a failure before the render starts only by its code
    std::string msg("Cannot open frame control '" + path + "': " + strerror(errno));
    fprintf(stderr, "%s\n", msg.c_str());
    throw POV_EXCEPTION_STRING(msg.c_str());
  }
  m_Path = path;
}

void FrameControl::Close()
{
  if (m_Fd >= 0)
    close(m_Fd);
  m_Fd = -1;
  m_Buffer.clear();
  m_Pending = false;
}

// Reads one line (without its newline); false at end of file.
bool FrameControl::ReadLine(std::string& line)
{
  for (;;)
  {
    size_t nl = m_Buffer.find('\n');
    if (nl != std::string::npos)
    {
      line = m_Buffer.substr(0, nl);
      m_Buffer.erase(0, nl + 1);
      return true;
    }
    char chunk[512];
    ssize_t n = read(m_Fd, chunk, sizeof(chunk));
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0)
      throw POV_EXCEPTION_STRING(("Cannot read frame control '" + m_Path + "': " + strerror(errno)).c_str());
    if (n == 0)
    {
      line = m_Buffer;
      m_Buffer.clear();
      return !line.empty();
    }
    m_Buffer.append(chunk, size_t(n));
  }
}

FrameControl::Action FrameControl::Next(int frame, POVMS_Object& frameOptions)
{
  while (!m_Pending)
  {
    std::string line, err;
    if (!ReadLine(line))
      return kStop;
    fc::ControlLine control;
    if (!fc::parse_control_line(line, control, err))
      throw POV_EXCEPTION_STRING(("Frame control: " + err).c_str());
    if (control.verb == fc::ControlLine::kNone)
      continue;
    if (control.verb == fc::ControlLine::kStop)
      return kStop;
    m_PendingFrame = control.frame;
    m_PendingRects.clear();
    for (size_t i = 0; i < control.rects.size(); i++)
    {
      m_PendingRects.push_back(control.rects[i].x0);
      m_PendingRects.push_back(control.rects[i].y0);
      m_PendingRects.push_back(control.rects[i].x1);
      m_PendingRects.push_back(control.rects[i].y1);
    }
    m_Pending = true;
  }
  if (m_PendingFrame > frame)
    return kSkip;
  if (m_PendingFrame < frame)
  {
    char msg[128];
    snprintf(msg, sizeof(msg), "Frame control asked for frame %d, but frame %d is next", m_PendingFrame, frame);
    throw POV_EXCEPTION_STRING(msg);
  }
  m_Pending = false;
  if (m_PendingRects.empty())
  {
    if (frameOptions.Exist(kPOVAttrib_RenderRectangles))
      frameOptions.Remove(kPOVAttrib_RenderRectangles);
  }
  else
    frameOptions.SetIntVector(kPOVAttrib_RenderRectangles, m_PendingRects);
  return kRender;
}

}
