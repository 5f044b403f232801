// output_format.cpp - the output format from POV-Ray's resolved options (see output_format.h).
#include "output_format.h"

#include <unistd.h>

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
    "fc-master writes Targa (+FT), RLE Targa (+FC), PNG (+FN) and OpenEXR (+FE)";

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

bool frame_size_possible(const OutputFormat &f, const std::string &encoding, int width, int height,
                         double memory_bytes, std::string &err)
{
    if (f.oiio == "targa" && (width > 65535 || height > 65535)) {
        err = strf("a %s frame holds at most 65535 pixels a side, not %dx%d: use PNG (+FN) or "
                   "OpenEXR (+FE)", f.name.c_str(), width, height);
        return false;
    }
    double pixels = double(width) * double(height);
    double sample = double(pixel_type_bytes(f.pixels));
    // The samples, the file of about their size, and the unquantized floats of diffusion.
    double need = pixels * 3 * sample * 2 + (encoding == "rgbf" ? pixels * 12 : 0);
    if (memory_bytes > 0 && need > memory_bytes) {
        err = strf("a frame of %dx%d pixels needs %s of fc-master's memory (its samples and its "
                   "file), more than this machine's %s", width, height, human_bytes(need).c_str(),
                   human_bytes(memory_bytes).c_str());
        return false;
    }
    return true;
}

double machine_memory()
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    return pages > 0 && size > 0 ? double(pages) * double(size) : 0;
}

std::string format_option(const OutputFormat &f)
{
    return f.type == 'N' ? strf("+FN%d", f.bits) : strf("+F%c", f.type);
}

std::string channel_encoding(const ResolvedOptions &ini, const OutputFormat &f)
{
    return f.pixels == PixelType::U8 && f.type != 'E' && diffusion(ini) ? "rgbf" : f.encoding;
}

} // namespace fc
