// output_format.h - the image format fc-master writes: the one POV-Ray would write with the
// same options, or a clear refusal.
//
// Targa (uncompressed) is the default, as in the paper: fc-master puts +FT before the user's
// options, so a format on the command line or in an INI file given there wins. Supported:
// Targa (+FT), RLE Targa (+FC), PNG (+FN, 5 to 16 bits per colour as POV-Ray stores them) and
// OpenEXR (+FE, half floats, linear). The renderer's frame channel carries each format's
// stored values (patch 0030), so the frames equal what one POV-Ray process writes.
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

// The format option for a user who named no format: +FN when Output_File_Name ends in
// ".png", +FE for ".exr" (as POV-Ray compares them: lower case), else +FT.
std::string format_from_name(const ResolvedOptions &ini);

// The frame-channel encoding the renderer sends for these options (patch 0030): "rgbf" under
// diffusion dithering, else the format's own.
std::string channel_encoding(const ResolvedOptions &ini, const OutputFormat &format);

} // namespace fc
