// Shared by the libFuzzer targets: a private scratch file per process, for
// readers that take a path (libtiff, the world-file reader).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace geocean::fuzz {

// "<dir>/geocean_fuzz_<pid>_<stem><ext>", dir = /dev/shm if present, else $TMPDIR or /tmp.
std::string scratchPath(const std::string& stem, const std::string& ext);
// Writes exactly the bytes (truncating); aborts if the file cannot be written.
void writeFile(const std::string& path, const std::uint8_t* data, std::size_t size);

}  // namespace geocean::fuzz
