// output_format.cpp - the output format from POV-Ray's resolved options (see output_format.h).
#include "output_format.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include "text.h"

namespace fc {

namespace {

bool diffusion(const ResolvedOptions &ini)
{
    if (!option_is_on(resolved_value(ini, "Dither", "off")))
        return false;
    std::string m = resolved_value(ini, "Dither_Method", "FS");
    for (char &c : m)
        c = char(toupper((unsigned char)c));
    return m == "D1" || m == "D2" || m == "FS";
}

const char *const kSupported =
    "fc-master writes Targa (+FT, the default), RLE Targa (+FC), PNG (+FN) and OpenEXR (+FE)";

} // namespace

bool output_format(const ResolvedOptions &ini, OutputFormat &f, std::string &err)
{
    f = OutputFormat();
    std::string type = resolved_value(ini, "Output_File_Type", "T");
    f.type = type.empty() ? 'T' : char(toupper((unsigned char)type[0]));
    switch (f.type) {
    case 'T':
        break;
    case 'C':
        f.name = "RLE Targa";
        f.compression = "rle";
        f.fixed_size = false;
        break;
    case 'N': {
        f.name = "PNG";
        f.oiio = "png";
        f.compression = "";
        f.ext = ".png";
        f.fixed_size = false;
        // POV-Ray clips Bits_Per_Color to 5..16 and stores 5-8 bits in bytes, 9-16 in words.
        int bits = atoi(resolved_value(ini, "Bits_Per_Color", "8").c_str());
        f.bits = std::min(16, std::max(5, bits));
        if (f.bits > 8) {
            f.pixels = PixelType::U16;
            f.encoding = "rgb16";
        }
        break;
    }
    case 'E':
        f.name = "OpenEXR";
        f.oiio = "openexr";
        f.compression = "zip";      // POV-Ray's (ZIP_COMPRESSION)
        f.ext = ".exr";
        f.bits = 16;
        f.pixels = PixelType::Half;
        f.encoding = "rgbl";
        f.fixed_size = false;
        break;
    default: {
        static const char *names[][2] = {{"J", "JPEG"}, {"P", "PPM"}, {"B", "BMP"},
                                         {"H", "Radiance HDR"}, {"S", "the system format"}};
        std::string what = "'" + type + "'";
        for (auto &n : names)
            if (f.type == n[0][0])
                what = n[1];
        err = strf("output file type %s (Output_File_Type=%c, +F%c) is not supported: %s",
                   what.c_str(), f.type, f.type, kSupported);
        return false;
    }
    }
    if (!option_is_on(resolved_value(ini, "Output_to_File", "on")) ||
        !option_is_on(resolved_value(ini, "Output_To_File", "on"))) {
        err = "Output_To_File is off (-F): fc-master exists to write the frames; drop the option";
        return false;
    }
    if (option_is_on(resolved_value(ini, "Output_Alpha", "off"))) {
        err = "Output_Alpha (+UA) is not supported: fc-master writes frames without an alpha "
              "channel";
        return false;
    }
    if (option_is_on(resolved_value(ini, "Grayscale_Output", "off"))) {
        err = "Grayscale_Output (+F...G) is not supported: fc-master writes colour frames";
        return false;
    }
    if (diffusion(ini) && f.pixels != PixelType::U8) {
        err = strf("diffusion dithering (Dither=on, Dither_Method %s) with %d bits per colour is "
                   "not supported: use Bits_Per_Color=8 or a Bayer method (B2, B3, B4)",
                   resolved_value(ini, "Dither_Method", "FS").c_str(), f.bits);
        return false;
    }
    return true;
}

std::string format_from_name(const ResolvedOptions &ini)
{
    std::string name = resolved_value(ini, "Output_File_Name", "");
    auto ends = [&](const char *ext) {
        size_t n = strlen(ext);
        return name.size() > n && name.compare(name.size() - n, n, ext) == 0;
    };
    return ends(".png") ? "+FN" : ends(".exr") ? "+FE" : "+FT";
}

std::string channel_encoding(const ResolvedOptions &ini, const OutputFormat &f)
{
    return f.pixels == PixelType::U8 && f.type != 'E' && diffusion(ini) ? "rgbf" : f.encoding;
}

} // namespace fc
