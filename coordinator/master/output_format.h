// output_format.h - the image format fc-master writes: the one POV-Ray would write with the
// same options, or a clear refusal.
//
// The format is POV-Ray's resolved Output_File_Type: what one povray-fc process writes with
// the same options and INI files (povray.ini included; Debian's says PNG). Supported:
// Targa (+FT), RLE Targa (+FC), PNG (+FN, 5 to 16 bits per colour as POV-Ray stores them) and
// OpenEXR (+FE, half floats, linear). The renderer's frame channel carries each format's
// stored values (the frame channel), so the frames equal what one POV-Ray process writes.
#pragma once

#include <string>

#include "image_codec.h"
#include "povray_probe.h"

namespace fc {

struct OutputFormat {
    char type = 'T';                // POV-Ray's Output_File_Type letter
    std::string name = "Targa";     // as POV-Ray calls it
    std::string oiio = "targa";     // OpenImageIO format name
    std::string compression = "none";
    std::string ext = ".tga";       // POV-Ray's file name extension
    int bits = 8;                   // bits per colour as stored
    PixelType pixels = PixelType::U8;
    std::string encoding = "rgb8";  // the frame channel's encoding of these pixels
    bool fixed_size = true;         // every frame encodes to the same number of bytes
};

// The format of POV-Ray's resolved options. False with err (naming the option and what would
// work) for what fc-master cannot write: other formats, alpha, grayscale, diffusion dithering
// at other than 8 bits, no output file.
bool output_format(const ResolvedOptions &ini, OutputFormat &format, std::string &err);

// Whether frames of width x height can be written at all, before anything renders: Targa holds
// at most 65535 pixels a side, and fc-master holds a frame in memory (its stored samples, and
// under diffusion dithering the unquantized values) and its file while it writes it, which
// must fit in memory_bytes (the machine's). False with a one-line reason.
bool frame_size_possible(const OutputFormat &format, const std::string &channel_encoding,
                         int width, int height, double memory_bytes, std::string &err);

// This machine's memory, bytes.
double machine_memory();

// The option that names this format (+FT, +FC, +FN8 ... +FN16, +FE): what the slaves'
// renderers get, so that they write what the master resolved whatever their own povray.ini.
std::string format_option(const OutputFormat &format);

// The frame-channel encoding the renderer sends for these options (the frame channel): "rgbf" under
// diffusion dithering, else the format's own.
std::string channel_encoding(const ResolvedOptions &ini, const OutputFormat &format);

} // namespace fc
