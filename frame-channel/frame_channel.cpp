/*******************************************************************************
 * frame_channel.cpp
 *
 * The frame channel (see frame_channel.h): one record per finished frame
 * (frame_record.h), pixels encoded as the output format's writer encodes them.
 *
 * This file is part of povray-fc and is licensed like POV-Ray (AGPL-3.0).
 *******************************************************************************/

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "vfe.h"
#include "base/image/encoding.h"
#include "base/povrayfc_povmsid.h"
#include "frame-channel/frame_channel.h"
#include "frame-channel/frame_record.h"
#include "frame-channel/option_ids.h"
#include "frame-channel/parse_reads.h"
#include "speedups/encode_memo.h"

// this must be the last file included
#include "base/povdebug.h"

namespace vfe
{

using namespace pov_base;

static double SteadySeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// An output stream into memory (an anonymous memory file, so that a writer may
// seek as in a file): the frame's image file, for a record of the whole image.
class MemoryOStream : public OStream
{
  public:
    MemoryOStream(unsigned int type) : OStream(type), m_Fd(memfd_create("povray-fc-frame", MFD_CLOEXEC))
    {
      // the stream gets a descriptor of its own: closing it leaves m_Fd to read back
      int fd = (m_Fd >= 0) ? dup(m_Fd) : -1;
      f = (fd >= 0) ? fdopen(fd, "w+b") : NULL;
      if ((f == NULL) && (fd >= 0))
        ::close(fd);
      fail = (f == NULL);
    }
    virtual ~MemoryOStream()
    {
      close();
      if (m_Fd >= 0)
        ::close(m_Fd);
    }
    // The bytes written; false when a write failed.
    bool Contents(std::vector<unsigned char>& out)
    {
      if (fail || (f == NULL) || (fflush(f) != 0))
        return false;
      off_t size = lseek(m_Fd, 0, SEEK_END);
      if (size < 0)
        return false;
      out.resize(size_t(size));
      size_t done = 0;
      while (done < out.size())
      {
        ssize_t n = pread(m_Fd, &out[done], out.size() - done, off_t(done));
        if (n < 0 && errno == EINTR)
          continue;
        if (n <= 0)
          return false;
        done += size_t(n);
      }
      return true;
    }
  private:
    int m_Fd;
};

// The rectangles of a frame that go into its record: those Frame_Control asked for
// (clipped to the image), else the whole image.
static std::vector<POVRect> FrameRectangles(POVMS_Object& opts, const Image& image)
{
  std::vector<POVRect> rects;
  int width = int(image.GetWidth()), height = int(image.GetHeight());
  if (opts.Exist(kPOVAttrib_RenderRectangles))
  {
    std::vector<POVMSInt> rr(opts.GetIntVector(kPOVAttrib_RenderRectangles));
    for (size_t i = 0; i + 3 < rr.size(); i += 4)
    {
      int x0 = max(0, int(rr[i])), y0 = max(0, int(rr[i + 1]));
      int x1 = min(width, int(rr[i + 2])), y1 = min(height, int(rr[i + 3]));
      if (x1 > x0 && y1 > y0)
        rects.push_back(POVRect(x0, y0, x1 - 1, y1 - 1));
    }
  }
  else
    rects.push_back(POVRect(0, 0, width - 1, height - 1));
  return rects;
}

// Error diffusion carries each pixel's error to pixels of other tiles, so a tile cannot be
// dithered alone: its values go out unquantized, and the receiver dithers the assembled frame
// (fc::is_diffusion_method names the methods by their numbers).
static_assert(kPOVList_DitherMethod_Diffusion1D == 1 && kPOVList_DitherMethod_Diffusion2D == 2 &&
              kPOVList_DitherMethod_FloydSteinberg == 3, "the frame record's dither method numbers");

// A gamma curve that records what it is asked to encode. GetEncodedRGBAValue with no dither
// offsets hands it exactly the red, green and blue values the Targa writer quantizes.
class RecordingGammaCurve : public GammaCurve
{
  public:
    RecordingGammaCurve() {}
    virtual ~RecordingGammaCurve() {}
    virtual float Encode(float x) const { values.push_back(x); return 0.0f; }
    virtual float Decode(float x) const { return 0.0f; }
    virtual float ApproximateDecodingGamma() const { return 1.0f; }
    mutable std::vector<float> values;
};

FrameChannel& FrameChannel::Get()
{
  static FrameChannel channel;
  return channel;
}

void FrameChannel::Open(POVMS_Object& opts)
{
  Close();
  std::string path(UCS2toASCIIString(opts.TryGetUCS2String(kPOVAttrib_FrameChannel, "")));
  if (path.empty())
    return;
  m_Fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (m_Fd < 0)
  {
    // said here: the console reports a failure before the render starts only by its code
    std::string msg("Cannot open frame channel '" + path + "': " + strerror(errno));
    fprintf(stderr, "%s\n", msg.c_str());
    throw POV_EXCEPTION_STRING(msg.c_str());
  }
  m_Path = path;
  // Each record says which files its frame's parse read (fc-master's resume checks them)
  fc::ParseReads::process().enable(true);
  // The frames go to the channel, so there is nothing to continue from: no render state
  // (.pov-state) file, which would be the renderer's only write to disk.
  opts.SetBool(kPOVAttrib_BackupTrace, false);
}

void FrameChannel::Close()
{
  if (m_Fd >= 0)
    close(m_Fd);
  m_Fd = -1;
  fc::ParseReads::process().enable(false);
}

void FrameChannel::ParseStarted()
{
  fc::ParseReads::process().restart();
  m_ParseStart = SteadySeconds();
  m_RenderStart = m_ParseStart;
  m_Rays = -1;
}

void FrameChannel::RenderStarted()
{
  m_RenderStart = SteadySeconds();
}

void FrameChannel::NoteStatistics(POVMS_Object& stats)
{
  m_Rays = stats.TryGetLong(kPOVAttrib_Rays, -1);
}

void FrameChannel::WriteAll(const void *data, size_t size)
{
  const char *p = static_cast<const char *>(data);
  while (size > 0)
  {
    ssize_t n = write(m_Fd, p, size);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      throw POV_EXCEPTION_STRING(("Cannot write to frame channel '" + m_Path + "': " + strerror(errno)).c_str());
    p += n;
    size -= size_t(n);
  }
}

// The stored value of a channel at bpcc bits, as the PNG writer packs it: 5 to 7 bits
// replicated into a byte, 9 to 15 into a 16-bit word (left-bit replication).
static unsigned int PackPNG(unsigned int v, int bpcc)
{
  if (bpcc < 8)
    return ((v << (8 - bpcc)) | (v >> (2 * bpcc - 8))) & 0xff;
  if (bpcc > 8 && bpcc < 16)
    return ((v << (16 - bpcc)) | (v >> (2 * bpcc - 16))) & 0xffff;
  return v;
}

static void PushWord(std::vector<unsigned char>& out, unsigned int v)
{
  out.push_back((unsigned char)(v & 0xff));     // little-endian
  out.push_back((unsigned char)(v >> 8));
}

void FrameChannel::WriteFrame(POVMS_Object& opts, pov_frontend::ImageProcessing& imageProcessing, int frame)
{
  const Image& image = *imageProcessing.GetImage();
  double now = SteadySeconds();

  // The output format decides what a pixel is (ImageProcessing::WriteImage and its writers):
  // Targa 8 bits non-premultiplied; PNG 5 to 16 bits, colour precomposed over black; OpenEXR
  // linear floats, premultiplied, no dithering. Other formats are the receiver's to refuse.
  int fileType = opts.TryGetInt(kPOVAttrib_OutputFileType, kPOVList_FileType_Targa);
  bool png = fileType == kPOVList_FileType_PNG;
  bool exr = fileType == kPOVList_FileType_OpenEXR;
  int bpcc = png ? clip(opts.TryGetInt(kPOVAttrib_BitsPerColor, 8), 5, 16) : 8;
  unsigned int maxValue = (1u << bpcc) - 1;

  // The encoding of ImageProcessing::WriteImage and the writers: file gamma over working
  // gamma (sRGB when none; OpenEXR: none, linear), the dither handler of the whole image.
  fc::Diffusion settings;
  settings.file_gamma_type = opts.TryGetInt(kPOVAttrib_FileGammaType, DEFAULT_FILE_GAMMA_TYPE);
  settings.file_gamma = opts.TryGetFloat(kPOVAttrib_FileGamma, DEFAULT_FILE_GAMMA);
  GammaCurvePtr encodingGamma = GetGammaCurve(settings.file_gamma_type, settings.file_gamma);
  settings.working_gamma_type = opts.TryGetInt(kPOVAttrib_WorkingGammaType, DEFAULT_WORKING_GAMMA_TYPE);
  settings.working_gamma = opts.TryGetFloat(kPOVAttrib_WorkingGamma, DEFAULT_WORKING_GAMMA);
  GammaCurvePtr workingGamma = GetGammaCurve(settings.working_gamma_type, settings.working_gamma);
  GammaCurvePtr gamma;
  if (exr)
    gamma = TranscodingGammaCurve::Get(workingGamma, NeutralGammaCurve::Get());
  else if (encodingGamma)
    gamma = TranscodingGammaCurve::Get(workingGamma, encodingGamma);
  else
    gamma = TranscodingGammaCurve::Get(workingGamma, SRGBGammaCurve::Get());
  int ditherMethod = kPOVList_DitherMethod_None;
  if (!exr && opts.TryGetBool(kPOVAttrib_Dither, false))
    ditherMethod = opts.TryGetInt(kPOVAttrib_DitherMethod, kPOVList_DitherMethod_FloydSteinberg);
  bool diffusion = fc::is_diffusion_method(ditherMethod);
  if (diffusion && bpcc != 8)
    throw POV_EXCEPTION_STRING("Frame channel: diffusion dithering is sent for 8 bits per colour only");
  DitherHandlerPtr dither(GetDitherHandler(diffusion ? kPOVList_DitherMethod_None : ditherMethod, image.GetWidth()));
  shared_ptr<RecordingGammaCurve> recorder(new RecordingGammaCurve());
  GammaCurvePtr encoder(diffusion ? GammaCurvePtr(recorder) : gamma);
  const char *encoding = diffusion ? "rgbf" : exr ? "rgbl" : bpcc > 8 ? "rgb16" : "rgb8";
  size_t perValue = exr ? sizeof(float) : bpcc > 8 ? 2 : 1;

  // povray-fc: with frame coherence most pixels are the last frame's; encode only the others,
  // as ImageProcessing::WriteImage does (not under diffusion: the recorder must see every value)
  povrayfc::EncodeMemo::SetEnabled(opts.TryGetBool(kPOVAttrib_FrameCoherence, false) && !diffusion);

  std::vector<POVRect> rects(FrameRectangles(opts, image));
  size_t bytes = 0;
  for (size_t i = 0; i < rects.size(); i++)
    bytes += size_t(rects[i].GetArea()) * 3;
  std::vector<unsigned char> pixels;
  pixels.reserve(bytes * perValue);
  recorder->values.reserve(diffusion ? bytes : 0);
  // povray-fc: for Targa, a span of a row whose stored floats are the last frame's bit for bit
  // comes from the memo whole, as the Targa writer does
  povrayfc::EncodeMemo *fcMemo = (!exr && !png && !diffusion) ? FC_EncodeMemo(&image, encoder, 255, *dither, false) : NULL;
  for (size_t i = 0; i < rects.size(); i++)
  {
    for (unsigned int y = rects[i].top; y <= rects[i].bottom; y++)
    {
      const float *fcRow = (fcMemo != NULL) ? image.FC_RowRGBFT(y) : NULL;
      for (unsigned int x = rects[i].left; x <= rects[i].right; x++)
      {
        if (fcRow != NULL)
        {
          // The memo's span holding x is compared and kept whole, also where it reaches past
          // the rectangle (a tile that does not start at a multiple of kSpan, as fc-master's
          // 80-pixel tiles mostly do); the rectangle's part of it is sent. The pixels outside
          // the rectangle are encoded from whatever this renderer's image holds there, which
          // the memo keys by its bits like any other pixel.
          const unsigned int fcFirst = x - x % povrayfc::EncodeMemo::kSpan;
          const unsigned int fcEnd = min(image.GetWidth(), fcFirst + povrayfc::EncodeMemo::kSpan) - 1;
          const unsigned int fcLast = min(fcEnd, rects[i].right);
          // only its pixels whose floats changed are encoded, into the memo
          fcMemo->RefreshSpan(fcFirst, y, fcRow + size_t(fcFirst) * 5, [&](unsigned int sx)
          {
            unsigned int r, g, b, a;
            GetEncodedRGBAValue(&image, sx, y, encoder, 255, r, g, b, a, *dither, false);
          });
          // the rectangle's part of the span at once (R, G, B a pixel)
          const size_t at = pixels.size();
          pixels.resize(at + size_t(fcLast - x + 1) * 3);
          unsigned char *put = &pixels[at];
          for (unsigned int sx = x; sx <= fcLast; sx++)
          {
            const std::uint16_t *out = fcMemo->Outputs(sx, y);
            *put++ = (unsigned char)out[0];
            *put++ = (unsigned char)out[1];
            *put++ = (unsigned char)out[2];
          }
          x = fcLast;
          continue;
        }
        if (exr)
        {
          float fr, fg, fb, fa;
          GetEncodedRGBAValue(&image, x, y, gamma, fr, fg, fb, fa, true);
          const float v[3] = { fr, fg, fb };
          const unsigned char *p = reinterpret_cast<const unsigned char *>(v);
          pixels.insert(pixels.end(), p, p + sizeof(v));
          continue;
        }
        unsigned int r, g, b, a;
        if (png)
          GetEncodedRGBValue(&image, x, y, encoder, maxValue, r, g, b, *dither);
        else
          GetEncodedRGBAValue(&image, x, y, encoder, 255, r, g, b, a, *dither, false);
        if (diffusion)
          continue;
        if (bpcc > 8)
        {
          PushWord(pixels, PackPNG(r, bpcc));
          PushWord(pixels, PackPNG(g, bpcc));
          PushWord(pixels, PackPNG(b, bpcc));
        }
        else
        {
          pixels.push_back((unsigned char)PackPNG(r, bpcc));
          pixels.push_back((unsigned char)PackPNG(g, bpcc));
          pixels.push_back((unsigned char)PackPNG(b, bpcc));
        }
      }
    }
  }
  if (diffusion)
  {
    if (recorder->values.size() != bytes)
      throw POV_EXCEPTION_STRING("Frame channel: unexpected number of encoded values");
    const unsigned char *p = reinterpret_cast<const unsigned char *>(&recorder->values[0]);
    pixels.assign(p, p + bytes * sizeof(float));
    // how the receiver dithers the assembled frame: POV-Ray's handler, through the same curve
    settings.method = ditherMethod;
    fc::append_diffusion(settings, pixels);
  }

  // A record of the whole image also carries the file Targa's or PNG's writer makes of it
  // (after the pixels above: they share the memo of encoded pixels, so the second pass
  // copies most spans). Without a memory file the record goes without: the pixels suffice.
  std::vector<unsigned char> file;
  bool whole = (rects.size() == 1) && (rects[0].left == 0) && (rects[0].top == 0) &&
               (rects[0].right + 1 == image.GetWidth()) && (rects[0].bottom + 1 == image.GetHeight());
  if (whole && (fileType == kPOVList_FileType_Targa || fileType == kPOVList_FileType_CompressedTarga || png))
  {
    MemoryOStream memory(png ? POV_File_Image_PNG : POV_File_Image_Targa);
    if (memory)
    {
      imageProcessing.WriteImage(opts, frame, 0, &memory);
      if (!memory.Contents(file))
        file.clear();
    }
  }

  fc::FrameRecord record;
  record.frame = frame;
  record.rays = double(m_Rays);
  record.parse_seconds = m_RenderStart - m_ParseStart;
  record.trace_seconds = now - m_RenderStart;
  record.encoding = encoding;
  for (size_t i = 0; i < rects.size(); i++)
  {
    fc::Rect r;
    r.x0 = int(rects[i].left);
    r.y0 = int(rects[i].top);
    r.x1 = int(rects[i].right) + 1;
    r.y1 = int(rects[i].bottom) + 1;
    record.rects.push_back(r);
  }
  // The gamma the format's writer records in the file (Targa's extension area): fc-master
  // writes an assembled frame with it, as one POV-Ray process would
  record.file_gamma = gamma->ApproximateDecodingGamma();
  record.data.swap(pixels);
  record.file.swap(file);
  record.reads = fc::ParseReads::process().take();
  const std::string header(fc::record_header(record));
  WriteAll(header.data(), header.size());
  if (!record.data.empty())
    WriteAll(&record.data[0], record.data.size());
  if (!record.file.empty())
    WriteAll(&record.file[0], record.file.size());
  if (!record.reads.empty())
    WriteAll(record.reads.data(), record.reads.size());
}

}
