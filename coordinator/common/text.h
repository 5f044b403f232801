// text.h - strings: printf into a std::string, trimming, prefixes, sizes for people.
#pragma once

#include <string>

namespace fc {

// printf into a std::string.
std::string strf(const char *format, ...) __attribute__((format(printf, 1, 2)));

// Trim spaces and tabs at both ends.
std::string trim(const std::string &s);

bool starts_with(const std::string &s, const std::string &prefix);
bool ends_with(const std::string &s, const std::string &suffix);

// "230 KB", "10.4 MB": a size for people.
std::string human_bytes(double bytes);

} // namespace fc
