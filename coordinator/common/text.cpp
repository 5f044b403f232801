// text.cpp - strings (see text.h).
#include "text.h"

#include <cstdarg>
#include <cstdio>

namespace fc {

std::string strf(const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    char small[512];
    va_list ap2;
    va_copy(ap2, ap);
    int n = vsnprintf(small, sizeof small, format, ap);
    va_end(ap);
    if (n < 0) {
        va_end(ap2);
        return std::string();
    }
    if (size_t(n) < sizeof small) {
        va_end(ap2);
        return std::string(small, size_t(n));
    }
    std::string out(size_t(n) + 1, '\0');
    vsnprintf(&out[0], out.size(), format, ap2);
    va_end(ap2);
    out.resize(size_t(n));
    return out;
}

std::string trim(const std::string &s)
{
    size_t a = s.find_first_not_of(" \t");
    if (a == std::string::npos)
        return std::string();
    size_t b = s.find_last_not_of(" \t");
    return s.substr(a, b - a + 1);
}

bool starts_with(const std::string &s, const std::string &prefix)
{
    return s.compare(0, prefix.size(), prefix) == 0;
}

bool ends_with(const std::string &s, const std::string &suffix)
{
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string human_bytes(double b)
{
    if (b < 1024)
        return strf("%.0f bytes", b);
    if (b < 1024.0 * 1024)
        return strf("%.0f KB", b / 1024);
    if (b < 1024.0 * 1024 * 1024)
        return strf("%.1f MB", b / (1024.0 * 1024));
    return strf("%.2f GB", b / (1024.0 * 1024 * 1024));
}

} // namespace fc
