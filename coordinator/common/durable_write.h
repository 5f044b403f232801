// durable_write.h - writing a file so that it is on disk, whole, or not there at all: how
// fc-master writes frames, manifests and the preview. A full disk is an error that says so,
// never a short file.
#pragma once

#include <cstddef>
#include <string>

namespace fc {

// Write bytes to path (created or truncated, mode 0644) and make them durable: every write,
// the fsync and the close are checked, and the file's size on disk must equal the bytes. On
// failure the file is removed and err names the call and errno's text ("No space left on
// device" for a full disk); errno is left as the failure set it.
bool write_file_durably(const std::string &path, const void *data, size_t size, std::string &err);

// fsync a directory, so that a rename in it survives a crash.
bool sync_dir(const std::string &dir, std::string &err);

} // namespace fc
